// make_feature_table: the 18 features of paper §3.3, formulas in docs/features.md.

#include "geometry/feature_table.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geometry/detail/parallel.hpp"
#include "geometry/errors.hpp"

namespace geotex {

int feature_index(const std::string& id) {
    for (int i = 0; i < kNumFeatures; ++i)
        if (id == kFeatureIds[i]) return i;
    return -1;
}

namespace {

using Vec3 = Eigen::Vector3d;

// One boundary loop of a texel: vertices in order, and the normal of the texel face on the
// inner side of each edge (edge i joins vertex i to vertex i+1).
struct Loop {
    std::vector<int> vertices;
    std::vector<Vec3> edge_face_normal;
};

struct Workspace {
    std::vector<double> vertex_weight;  // #V scratch, zero outside the current texel
    std::vector<int> touched;
};

// Area-weighted mean and population standard deviation of `value` over the texel
// vertices, skipping NaN; (0, 0, false) when no vertex has a value.
struct WeightedStats {
    double mean = 0, std = 0;
    bool defined = false;
};
template <class ValueOf>
WeightedStats weighted_stats(const std::vector<int>& vertices, const std::vector<double>& weight,
                             ValueOf&& value_of) {
    double sw = 0, sx = 0;
    for (int v : vertices) {
        const double x = value_of(v);
        if (std::isnan(x)) continue;
        sw += weight[v];
        sx += weight[v] * x;
    }
    WeightedStats s;
    if (!(sw > 0)) return s;
    s.mean = sx / sw;
    double sq = 0;
    for (int v : vertices) {
        const double x = value_of(v);
        if (!std::isnan(x)) sq += weight[v] * (x - s.mean) * (x - s.mean);
    }
    s.std = std::sqrt(sq / sw);
    s.defined = true;
    return s;
}

// Boundary loops of the face set {f : owner[f] == id}: half-edges of its faces whose edge
// has no other face of the set, chained head to tail (paper §3.3.1, the contour C).
std::vector<Loop> boundary_loops(const Mesh& mesh, const MeshTopology& topology,
                                 const std::vector<int>& owner, int id, const std::vector<int>& faces,
                                 const std::vector<Vec3>& face_normal) {
    struct HalfEdge {
        int from, to, face;
    };
    std::vector<HalfEdge> half_edges;
    for (int f : faces) {
        const auto& fv = mesh.faces[f];
        for (int k = 0; k < 3; ++k) {
            const int a = fv[k], b = fv[(k + 1) % 3];
            int in_set = 0;
            for (int g : topology.faces_of(a)) {
                const auto& gv = mesh.faces[g];
                if (owner[g] == id && (gv[0] == b || gv[1] == b || gv[2] == b)) ++in_set;
            }
            if (in_set == 1) half_edges.push_back({a, b, f});
        }
    }
    std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
        return x.from != y.from ? x.from < y.from : x.to < y.to;
    });
    std::vector<char> used(half_edges.size(), 0);
    std::vector<Loop> loops;
    for (std::size_t start = 0; start < half_edges.size(); ++start) {
        if (used[start]) continue;
        Loop loop;
        std::size_t cur = start;
        while (true) {
            used[cur] = 1;
            loop.vertices.push_back(half_edges[cur].from);
            loop.edge_face_normal.push_back(face_normal[half_edges[cur].face]);
            const int next_from = half_edges[cur].to;
            if (next_from == half_edges[start].from) break;
            // First unused half-edge leaving next_from (several only at pinch vertices).
            auto it = std::lower_bound(half_edges.begin(), half_edges.end(), next_from,
                                       [](const HalfEdge& h, int v) { return h.from < v; });
            std::size_t next = half_edges.size();
            for (; it != half_edges.end() && it->from == next_from; ++it)
                if (!used[it - half_edges.begin()]) {
                    next = static_cast<std::size_t>(it - half_edges.begin());
                    break;
                }
            if (next == half_edges.size()) break;  // open chain at a non-manifold spot
            cur = next;
        }
        loops.push_back(std::move(loop));
    }
    return loops;
}

double loop_length(const std::vector<Vec3>& points) {
    double length = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
        length += (points[(i + 1) % points.size()] - points[i]).norm();
    return length;
}

// Local diameters of a closed smoothed contour (paper §3.3.1, "local diameter"): for each
// edge, the plane through its midpoint orthogonal to it cuts other contour edges; the
// distance to the nearest cut on the inner side (towards the texel) is the local diameter.
std::vector<double> local_diameters(const std::vector<Vec3>& c, const std::vector<Vec3>& inner_normal) {
    const std::size_t m = c.size();
    std::vector<double> out;
    if (m < 3) return out;
    for (std::size_t i = 0; i < m; ++i) {
        const Vec3 a = c[i], b = c[(i + 1) % m];
        const Vec3 edge = b - a;
        const double len = edge.norm();
        if (!(len > 0)) continue;
        const Vec3 t = edge / len, mid = 0.5 * (a + b);
        const Vec3 inward = inner_normal[i].cross(t);  // faces lie left of their edges
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < m; ++j) {
            if (j == i || j == (i + 1) % m || (j + 1) % m == i) continue;
            const Vec3 p = c[j], q = c[(j + 1) % m];
            const double sp = (p - mid).dot(t), sq = (q - mid).dot(t);
            if (!((sp <= 0 && sq > 0) || (sq <= 0 && sp > 0))) continue;  // half-open: count once
            const Vec3 x = p + (sp / (sp - sq)) * (q - p);
            const Vec3 d = x - mid;
            if (d.dot(inward) <= 0) continue;
            best = std::min(best, d.norm());
        }
        if (std::isfinite(best)) out.push_back(best);
    }
    return out;
}

}  // namespace

FeatureTable make_feature_table(const FeatureInputs& in, const std::vector<Texel>& texels) {
    if (!in.mesh || !in.topology || !in.curvature || !(in.largest_side > 0))
        throw InvalidInput("features: mesh, topology, curvature and a positive largest_side are required");
    const Mesh& mesh = *in.mesh;
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    const int nt = static_cast<int>(texels.size());
    for (const auto& t : texels) {
        const DepthMap* d = t.orientation == DetailOrientation::Positive ? in.positive_depth : in.negative_depth;
        if (!d) throw InvalidInput("features: a texel's orientation has no depth map");
        if (static_cast<int>(d->vertex_depth.size()) != nv)
            throw InvalidInput("features: a depth map does not match the mesh");
    }
    const double s = 1.0 / in.largest_side;  // to the unit-side mesh

    std::vector<int> owner(nf, -1);
    for (int i = 0; i < nt; ++i) {
        if (texels[i].faces.empty()) throw InvalidInput("features: texel " + std::to_string(i) + " has no face");
        for (int f : texels[i].faces) {
            if (f < 0 || f >= nf) throw InvalidInput("features: texel " + std::to_string(i) + " has a face out of range");
            if (owner[f] != -1)
                throw InvalidInput("features: face " + std::to_string(f) + " belongs to texels " +
                                   std::to_string(owner[f]) + " and " + std::to_string(i));
            owner[f] = i;
        }
    }
    std::vector<Vec3> face_normal(nf, Vec3::Zero());
    detail::parallel_for(nf, [&](int f) {
        const auto& p = mesh.positions;
        const auto& fv = mesh.faces[f];
        const Vec3 n = (p[fv[1]] - p[fv[0]]).cross(p[fv[2]] - p[fv[0]]);
        if (n.norm() > 0) face_normal[f] = n.normalized();
    });

    FeatureTable table;
    table.names.assign(kFeatureIds.begin(), kFeatureIds.end());
    table.values = Eigen::MatrixXd::Zero(nt, kNumFeatures);
    std::vector<std::vector<double>> diameters(nt);
    std::vector<char> no_contour(nt, 0), no_curvature(nt, 0);
    auto col = [](Feature f) { return static_cast<int>(f); };

    detail::parallel_for_with(
        nt, [&] { return Workspace{std::vector<double>(nv, 0.0), {}}; },
        [&](int i, Workspace& ws) {
            const Texel& texel = texels[i];
            auto row = table.values.row(i);
            const auto& p = mesh.positions;
            // Vertices of the texel, weighted by a third of their texel-face area.
            ws.touched.clear();
            double area = 0;
            Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
            Vec3 first_moment = Vec3::Zero();
            const Vec3 origin = p[mesh.faces[texel.faces.front()][0]];
            for (int f : texel.faces) {
                const auto& fv = mesh.faces[f];
                const Vec3 a = s * (p[fv[0]] - origin), b = s * (p[fv[1]] - origin),
                           c = s * (p[fv[2]] - origin);
                const double fa = 0.5 * (b - a).cross(c - a).norm();
                area += fa;
                const Vec3 sum = a + b + c;
                first_moment += fa * sum / 3.0;
                // Exact second moment of a uniform triangle: A/12 (aa' + bb' + cc' + ss').
                second += fa / 12.0 *
                          (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
                for (int v : fv) {
                    if (ws.vertex_weight[v] == 0) ws.touched.push_back(v);
                    ws.vertex_weight[v] += fa / 3.0;
                }
            }
            std::sort(ws.touched.begin(), ws.touched.end());  // fixed summation order
            const Vec3 centroid = area > 0 ? Vec3(first_moment / area) : Vec3::Zero();
            double bounding_radius = 0;
            for (int v : ws.touched)
                bounding_radius = std::max(bounding_radius, (s * (p[v] - origin) - centroid).norm());
            row(col(Feature::Area)) = area;  // min-max normalised over the texels below
            row(col(Feature::BoundingSphereRadius)) = bounding_radius;
            row(col(Feature::AreaRel)) = area;  // the unit-side mesh: fractions of the side
            row(col(Feature::BoundingSphereRadiusRel)) = bounding_radius;

            // PCA of the surface: eigenvalues of its covariance, divided by their sum.
            if (area > 0) {
                const Eigen::Matrix3d cov = second / area - centroid * centroid.transpose();
                Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov, Eigen::EigenvaluesOnly);
                Vec3 ev = eig.eigenvalues().cwiseMax(0.0);  // ascending
                const double total = ev.sum();
                if (total > 0) {
                    row(col(Feature::PcaVariance1)) = ev(2) / total;
                    row(col(Feature::PcaVariance2)) = ev(1) / total;
                    row(col(Feature::PcaVariance3)) = ev(0) / total;
                }
            }

            // Contour features on the longest boundary loop, smoothed with (1/4, 1/2, 1/4).
            const auto loops = boundary_loops(mesh, *in.topology, owner, i, texel.faces, face_normal);
            const Loop* main = nullptr;
            double main_length = -1;
            for (const auto& loop : loops) {
                std::vector<Vec3> pts;
                for (int v : loop.vertices) pts.push_back(s * (p[v] - origin));
                const double len = loop_length(pts);
                if (len > main_length) {
                    main_length = len;
                    main = &loop;
                }
            }
            if (main && main->vertices.size() >= 3) {
                const std::size_t m = main->vertices.size();
                std::vector<Vec3> raw(m), smooth(m);
                for (std::size_t k = 0; k < m; ++k) raw[k] = s * (p[main->vertices[k]] - origin);
                for (std::size_t k = 0; k < m; ++k)
                    smooth[k] = 0.25 * (raw[(k + m - 1) % m] + 2 * raw[k] + raw[(k + 1) % m]);
                const double perimeter = loop_length(smooth);
                row(col(Feature::ContourPerimeter)) = perimeter;
                row(col(Feature::Perimeter2AreaRatio)) = area > 0 ? perimeter * perimeter / area : 0.0;
                if (bounding_radius > 0) {
                    double sum = 0, sq = 0;
                    for (const auto& q : smooth) {
                        const double d = (bounding_radius - (q - centroid).norm()) / bounding_radius;
                        sum += d;
                        sq += d * d;
                    }
                    const double mean = sum / static_cast<double>(m);
                    row(col(Feature::ContourSphericity)) = std::sqrt(std::max(0.0, sq / static_cast<double>(m) - mean * mean));
                }
                diameters[i] = local_diameters(smooth, main->edge_face_normal);
            } else {
                no_contour[i] = 1;
            }

            // Local aspect: depth (normalised by the largest depth of the map) and curvature
            // (in units of the unit-side mesh), area-weighted over the texel's vertices.
            const DepthMap& dm = texel.orientation == DetailOrientation::Positive ? *in.positive_depth : *in.negative_depth;
            const double depth_scale = dm.max_depth > 0 ? 1.0 / dm.max_depth : 0.0;
            const auto& w = ws.vertex_weight;
            const auto& cv = *in.curvature;
            const double L = in.largest_side;
            const auto depth = weighted_stats(ws.touched, w, [&](int v) { return dm.vertex_depth[v] * depth_scale; });
            const auto gauss = weighted_stats(ws.touched, w, [&](int v) { return cv.gaussian[v] * L * L; });
            const auto shape = weighted_stats(ws.touched, w, [&](int v) { return cv.shape_index[v]; });
            const auto curved = weighted_stats(ws.touched, w, [&](int v) { return cv.curvedness[v] * L; });
            row(col(Feature::DepthMean)) = depth.mean;
            row(col(Feature::DepthStd)) = depth.std;
            row(col(Feature::GaussianCurvatureMean)) = gauss.mean;
            row(col(Feature::GaussianCurvatureStd)) = gauss.std;
            row(col(Feature::ShapeIndexMean)) = shape.mean;
            row(col(Feature::ShapeIndexStd)) = shape.std;
            row(col(Feature::CurvednessMean)) = curved.mean;
            row(col(Feature::CurvednessStd)) = curved.std;
            if (!gauss.defined) no_curvature[i] = 1;
            for (int v : ws.touched) ws.vertex_weight[v] = 0;
        },
        1);

    // Normalisations across texels: local diameters by the largest over all contours;
    // area and bounding sphere radius min-max (0 when all texels are equal).
    double max_diameter = 0;
    for (const auto& d : diameters)
        for (double x : d) max_diameter = std::max(max_diameter, x);
    for (int i = 0; i < nt; ++i) {
        if (diameters[i].empty() || !(max_diameter > 0)) continue;
        double sum = 0, sq = 0;
        for (double x : diameters[i]) sum += x / max_diameter;
        const double mean = sum / static_cast<double>(diameters[i].size());
        for (double x : diameters[i]) sq += (x / max_diameter - mean) * (x / max_diameter - mean);
        table.values(i, col(Feature::LocalDiameterMean)) = mean;
        table.values(i, col(Feature::LocalDiameterStd)) = std::sqrt(sq / static_cast<double>(diameters[i].size()));
    }
    for (Feature f : {Feature::Area, Feature::BoundingSphereRadius}) {
        if (nt == 0) break;
        auto column = table.values.col(col(f));
        const double lo = column.minCoeff(), hi = column.maxCoeff();
        for (int i = 0; i < nt; ++i) column(i) = hi > lo ? (column(i) - lo) / (hi - lo) : 0.0;
    }
    int n_no_contour = 0, n_no_curvature = 0;
    for (int i = 0; i < nt; ++i) {
        n_no_contour += no_contour[i];
        n_no_curvature += no_curvature[i];
    }
    if (n_no_contour > 0)
        table.diagnostics.push_back({"features", std::to_string(n_no_contour) +
                                                     " texels have no boundary (a whole closed component): contour features set to 0"});
    if (n_no_curvature > 0)
        table.diagnostics.push_back({"features", std::to_string(n_no_curvature) +
                                                     " texels have only border vertices: curvature features set to 0"});
    return table;
}

}  // namespace geotex
