// make_feature_table: the 18 features of paper §3.3, formulas in docs/features.md.

#include "geometry/feature_table.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/errors.hpp"
#include "geometry/detail/contour.hpp"
#include "geometry/detail/parallel.hpp"

namespace geotex {

int feature_index(const std::string& id) {
    for (int i = 0; i < kNumFeatures; ++i)
        if (id == kFeatureIds[i]) return i;
    return -1;
}

namespace {

using Vec3 = Eigen::Vector3d;

// One boundary loop of a texel: vertices in order and, for each edge (edge i joins vertex i
// to vertex i+1), the texel face on its inner side and the face across it (-1 on a mesh
// border or when every face across is in the texel).
struct Loop {
    std::vector<int> vertices;
    std::vector<int> inner_face, outer_face;
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
                                 const std::vector<int>& owner, int id,
                                 const std::vector<int>& faces) {
    struct HalfEdge {
        int from, to, face, outer;
    };
    std::vector<HalfEdge> half_edges;
    for (int f : faces) {
        const auto& fv = mesh.faces[f];
        for (int k = 0; k < 3; ++k) {
            const int a = fv[k], b = fv[(k + 1) % 3];
            int in_set = 0, outer = -1;
            for (int g : topology.faces_of(a)) {
                const auto& gv = mesh.faces[g];
                if (!(gv[0] == b || gv[1] == b || gv[2] == b)) continue;
                if (owner[g] == id)
                    ++in_set;
                else if (outer < 0)
                    outer = g;
            }
            if (in_set == 1) half_edges.push_back({a, b, f, outer});
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
            loop.inner_face.push_back(half_edges[cur].face);
            loop.outer_face.push_back(half_edges[cur].outer);
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

// The contour of a texel at sub-face precision: one point per edge of its boundary loop,
// where the face depth, interpolated from the centre of the inner face f to the centre of the
// face g across the edge, reaches the texel's threshold t (the texel is the faces with
// depth >= t, so this is the iso-line of the segmentation's own criterion, and it no longer
// zigzags along the face edges). Where the depths do not straddle t (a mesh border, another
// texel across, or a face that joined the texel at the lower threshold of a merged region),
// the point is the edge's midpoint. Point k lies on edge k, so the contour edge k turns
// around loop vertex k+1; `inner_normal` gets the mean of the normals of faces k and k+1.
struct Contour {
    std::vector<Vec3> points, inner_normal;
};
Contour iso_contour(const Mesh& mesh, const Loop& loop, const DepthMap& depth, double threshold,
                    double s, const Vec3& origin) {
    const auto& p = mesh.positions;
    // Only the faces along the loop need a normal: computed here rather than kept for every
    // face of the mesh (24 bytes a face).
    auto face_normal = [&](int f) -> Vec3 {
        const auto& fv = mesh.faces[f];
        const Vec3 n = (p[fv[1]] - p[fv[0]]).cross(p[fv[2]] - p[fv[0]]);
        return n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
    };
    auto centre = [&](int f) {
        const auto& fv = mesh.faces[f];
        return Vec3(s * ((p[fv[0]] + p[fv[1]] + p[fv[2]]) / 3.0 - origin));
    };
    const std::size_t m = loop.vertices.size();
    Contour c;
    c.points.resize(m);
    c.inner_normal.resize(m);
    for (std::size_t k = 0; k < m; ++k) {
        const int a = loop.vertices[k], b = loop.vertices[(k + 1) % m];
        const int f = loop.inner_face[k], g = loop.outer_face[k];
        c.points[k] = s * (0.5 * (p[a] + p[b]) - origin);
        if (g >= 0) {
            const double df = depth.face_depth[f], dg = depth.face_depth[g];
            if (df >= threshold && dg < threshold)
                c.points[k] = centre(f) + ((df - threshold) / (df - dg)) * (centre(g) - centre(f));
        }
        const Vec3 nf = face_normal(f);
        const Vec3 n = nf + face_normal(loop.inner_face[(k + 1) % m]);
        c.inner_normal[k] = n.norm() > 0 ? Vec3(n.normalized()) : nf;
    }
    return c;
}

// Local diameters of a closed contour (paper §3.3.1, "local diameter"): for each edge, the
// plane through its midpoint orthogonal to it cuts other contour edges; the distance to the
// nearest cut on the inner side (towards the texel) is the local diameter. Each comes with
// its edge's length as weight.
using WeightedValue = FeatureRows::Diameter;
std::vector<WeightedValue> local_diameters(const std::vector<Vec3>& c,
                                           const std::vector<Vec3>& inner_normal) {
    const std::size_t m = c.size();
    std::vector<WeightedValue> out;
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
        if (std::isfinite(best)) out.push_back({best, len});
    }
    return out;
}

// The column of a feature in the table.
constexpr int col(Feature f) { return static_cast<int>(f); }

}  // namespace

FeatureRows make_feature_rows(const FeatureInputs& in, const std::vector<Texel>& texels) {
    if (!in.mesh || !in.topology || !in.curvature || !(in.largest_side > 0))
        throw InvalidInput(
            "features: mesh, topology, curvature and a positive largest_side are required");
    expect_vertex_faces(*in.mesh, *in.topology, "features");
    const Mesh& mesh = *in.mesh;
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    const int nt = static_cast<int>(texels.size());
    for (const auto& t : texels) {
        const DepthMap* d =
            t.orientation == DetailOrientation::Positive ? in.positive_depth : in.negative_depth;
        if (!d) throw InvalidInput("features: a texel's orientation has no depth map");
        if (static_cast<int>(d->vertex_depth.size()) != nv)
            throw InvalidInput("features: a depth map does not match the mesh");
    }
    const double s = 1.0 / in.largest_side;  // to the unit-side mesh

    std::vector<int> owner(nf, -1);
    for (int i = 0; i < nt; ++i) {
        if (texels[i].faces.empty())
            throw InvalidInput("features: texel " + std::to_string(i) + " has no face");
        for (int f : texels[i].faces) {
            if (f < 0 || f >= nf)
                throw InvalidInput("features: texel " + std::to_string(i) +
                                   " has a face out of range");
            if (owner[f] != -1)
                throw InvalidInput("features: face " + std::to_string(f) + " belongs to texels " +
                                   std::to_string(owner[f]) + " and " + std::to_string(i));
            owner[f] = i;
        }
    }

    FeatureRows rows;
    rows.values = Eigen::MatrixXd::Zero(nt, kNumFeatures);
    rows.diameters.resize(nt);
    rows.no_contour.assign(nt, 0);
    rows.no_curvature.assign(nt, 0);
    auto& diameters = rows.diameters;
    auto& no_contour = rows.no_contour;
    auto& no_curvature = rows.no_curvature;

    detail::parallel_for_with(
        nt,
        [&] {
            return Workspace{std::vector<double>(nv, 0.0), {}};
        },
        [&](int i, Workspace& ws) {
            const Texel& texel = texels[i];
            auto row = rows.values.row(i);
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
                          (a * a.transpose() + b * b.transpose() + c * c.transpose() +
                           sum * sum.transpose());
                for (int v : fv) {
                    if (ws.vertex_weight[v] == 0) ws.touched.push_back(v);
                    ws.vertex_weight[v] += fa / 3.0;
                }
            }
            std::sort(ws.touched.begin(), ws.touched.end());  // fixed summation order
            const Vec3 centroid = area > 0 ? Vec3(first_moment / area) : Vec3::Zero();
            double bounding_radius = 0;
            for (int v : ws.touched)
                bounding_radius =
                    std::max(bounding_radius, (s * (p[v] - origin) - centroid).norm());
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

            // Contour features on the iso-line along the longest boundary loop.
            const DepthMap& dm = texel.orientation == DetailOrientation::Positive
                                     ? *in.positive_depth
                                     : *in.negative_depth;
            const auto loops = boundary_loops(mesh, *in.topology, owner, i, texel.faces);
            const Loop* main = nullptr;
            double main_length = -1;
            for (const auto& loop : loops) {
                std::vector<Vec3> pts;
                for (int v : loop.vertices) pts.push_back(s * (p[v] - origin));
                const double len = detail::closed_length(pts);
                if (len > main_length) {
                    main_length = len;
                    main = &loop;
                }
            }
            if (main && main->vertices.size() >= 3) {
                const Contour contour = iso_contour(mesh, *main, dm, texel.threshold, s, origin);
                const std::vector<Vec3>& c = contour.points;
                const double perimeter = detail::closed_length(c);
                row(col(Feature::ContourPerimeter)) = perimeter;
                row(col(Feature::Perimeter2AreaRatio)) =
                    area > 0 ? perimeter * perimeter / area : 0.0;
                if (bounding_radius > 0) {
                    std::vector<double> d(c.size());
                    for (std::size_t k = 0; k < c.size(); ++k)
                        d[k] = (bounding_radius - (c[k] - centroid).norm()) / bounding_radius;
                    row(col(Feature::ContourSphericity)) =
                        detail::weighted_mean_std(d, detail::arc_weights(c)).std;
                }
                diameters[i] = local_diameters(c, contour.inner_normal);
            } else {
                no_contour[i] = 1;
            }

            // Local aspect: depth (normalised by the largest depth of the map) and curvature
            // (in units of the unit-side mesh), area-weighted over the texel's vertices.
            const double depth_scale = dm.max_depth > 0 ? 1.0 / dm.max_depth : 0.0;
            const auto& w = ws.vertex_weight;
            const auto& cv = *in.curvature;
            const double L = in.largest_side;
            const auto depth = weighted_stats(
                ws.touched, w, [&](int v) { return dm.vertex_depth[v] * depth_scale; });
            const auto gauss =
                weighted_stats(ws.touched, w, [&](int v) { return cv.gaussian[v] * L * L; });
            const auto shape =
                weighted_stats(ws.touched, w, [&](int v) { return cv.shape_index[v]; });
            const auto curved =
                weighted_stats(ws.touched, w, [&](int v) { return cv.curvedness[v] * L; });
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
    return rows;
}

FeatureTable normalise_feature_rows(FeatureRows rows) {
    const int nt = static_cast<int>(rows.values.rows());
    if (static_cast<int>(rows.diameters.size()) != nt ||
        static_cast<int>(rows.no_contour.size()) != nt ||
        static_cast<int>(rows.no_curvature.size()) != nt || rows.values.cols() != kNumFeatures)
        throw InvalidInput("features: the rows' parts do not have one entry per texel");
    FeatureTable table;
    table.names.assign(kFeatureIds.begin(), kFeatureIds.end());
    table.values = std::move(rows.values);
    const auto& diameters = rows.diameters;
    const auto& no_contour = rows.no_contour;
    const auto& no_curvature = rows.no_curvature;

    // Normalisations across texels: local diameters by the largest over all contours;
    // area and bounding sphere radius min-max (0 when all texels are equal).
    double max_diameter = 0;
    for (const auto& d : diameters)
        for (const auto& x : d) max_diameter = std::max(max_diameter, x.value);
    for (int i = 0; i < nt; ++i) {
        if (diameters[i].empty() || !(max_diameter > 0)) continue;
        std::vector<double> x, w;
        for (const auto& d : diameters[i]) {
            x.push_back(d.value / max_diameter);
            w.push_back(d.weight);
        }
        const auto stats = detail::weighted_mean_std(x, w);
        table.values(i, col(Feature::LocalDiameterMean)) = stats.mean;
        table.values(i, col(Feature::LocalDiameterStd)) = stats.std;
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
        table.diagnostics.push_back(
            {"features",
             std::to_string(n_no_contour) +
                 " texels have no boundary (a whole closed component): contour features set to 0"});
    if (n_no_curvature > 0)
        table.diagnostics.push_back(
            {"features", std::to_string(n_no_curvature) +
                             " texels have only border vertices: curvature features set to 0"});
    return table;
}

FeatureTable make_feature_table(const FeatureInputs& in, const std::vector<Texel>& texels) {
    return normalise_feature_rows(make_feature_rows(in, texels));
}

}  // namespace geotex
