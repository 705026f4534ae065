#include "geometry/topology.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "common/release.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/union_find.hpp"

namespace geotex {

namespace {

// Counting sort of the face corners into per-vertex rows; rows come out sorted because
// faces are visited in increasing order.
void build_vertex_faces(const Mesh& mesh, MeshTopology& t) {
    const int nv = mesh.num_vertices();
    t.vertex_face_offsets.assign(nv + 1, 0);
    for (const auto& f : mesh.faces)
        for (int v : f) ++t.vertex_face_offsets[v + 1];
    for (int v = 0; v < nv; ++v) t.vertex_face_offsets[v + 1] += t.vertex_face_offsets[v];
    t.vertex_faces.resize(t.vertex_face_offsets[nv]);
    std::vector<int> fill(t.vertex_face_offsets.begin(), t.vertex_face_offsets.end() - 1);
    for (int f = 0; f < mesh.num_faces(); ++f)
        for (int v : mesh.faces[f]) t.vertex_faces[fill[v]++] = f;
}

// Calls fn(g) for each face g of `faces_of_a` that also contains vertex b.
template <class Fn>
void for_each_face_on_edge(const Mesh& mesh, IndexRange faces_of_a, int b, Fn&& fn) {
    for (int g : faces_of_a) {
        const auto& fg = mesh.faces[g];
        if (fg[0] == b || fg[1] == b || fg[2] == b) fn(g);
    }
}

// The other vertices of each vertex's faces, sorted and unique (vertex_faces built). Its
// scratch, two vertices an incident face (24 bytes a face), is freed on return, before
// make_topology makes the faces' rows.
void build_vertex_neighbours(const Mesh& mesh, MeshTopology& t) {
    const int nv = mesh.num_vertices();
    std::vector<int> degree(nv, 0);
    std::vector<int> bound_offsets(nv + 1, 0);  // two other vertices per incident face
    for (int v = 0; v < nv; ++v) bound_offsets[v + 1] = bound_offsets[v] + 2 * t.faces_of(v).size();
    std::vector<int> scratch(bound_offsets[nv]);
    detail::parallel_for(nv, [&](int v) {
        int* out = scratch.data() + bound_offsets[v];
        int n = 0;
        for (int f : t.faces_of(v))
            for (int u : mesh.faces[f])
                if (u != v) out[n++] = u;
        std::sort(out, out + n);
        degree[v] = static_cast<int>(std::unique(out, out + n) - out);
    });
    t.vertex_neighbour_offsets.assign(nv + 1, 0);
    for (int v = 0; v < nv; ++v)
        t.vertex_neighbour_offsets[v + 1] = t.vertex_neighbour_offsets[v] + degree[v];
    t.vertex_neighbours.resize(t.vertex_neighbour_offsets[nv]);
    detail::parallel_for(nv, [&](int v) {
        std::copy_n(scratch.data() + bound_offsets[v], degree[v],
                    t.vertex_neighbours.data() + t.vertex_neighbour_offsets[v]);
    });
}

}  // namespace

namespace {

// The components of the vertices joined by the faces each_block(fn) hands to fn, a block at a
// time: the mesh's own faces, or a file's read in blocks.
template <class EachBlock>
VertexComponents components_of(int nv, EachBlock&& each_block) {
    detail::UnionFind parts(nv);
    each_block([&](const std::vector<std::array<int, 3>>& faces) {
        for (const auto& f : faces) {
            parts.unite(f[0], f[1]);
            parts.unite(f[0], f[2]);
        }
    });
    VertexComponents c;
    c.component.assign(nv, -1);
    for (int v = 0; v < nv; ++v) {
        const int root = parts.find(v);
        c.component[v] = root == v ? c.num_components++ : c.component[root];
    }
    return c;
}

}  // namespace

VertexComponents vertex_components(const Mesh& mesh) {
    return components_of(mesh.num_vertices(), [&](auto&& fn) { fn(mesh.faces); });
}

VertexComponents vertex_components(int num_vertices, const FaceBlockReader& faces,
                                   std::size_t num_faces) {
    return components_of(num_vertices, [&](auto&& fn) {
        for_each_face_block(faces, num_faces, [&](std::size_t, const auto& block) { fn(block); });
    });
}

MeshTopology make_topology(const Mesh& mesh, TopologyRows rows) {
    const int nv = mesh.num_vertices();
    const int nf = mesh.num_faces();
    for (int f = 0; f < nf; ++f)
        for (int v : mesh.faces[f])
            if (v < 0 || v >= nv)
                throw InvalidInput("topology: face " + std::to_string(f) + " has vertex index " +
                                   std::to_string(v) + " outside [0, " + std::to_string(nv) + ")");
    MeshTopology t;
    build_vertex_faces(mesh, t);

    build_vertex_neighbours(mesh, t);

    // Face neighbours through each of the three edges; count boundary and non-manifold
    // edges once, from the face of smallest index on the edge.
    std::vector<int> face_degree(nf, 0);
    std::vector<int> boundary_count(nf, 0), non_manifold_count(nf, 0);
    std::vector<unsigned char> odd_edges(
        nf, 0);  // bit k: edge k of the face has one face or more than two
    t.vertex_on_boundary.assign(nv, 0);
    auto edge_scan = [&](int f, int* out, bool fill) {
        int n = 0;
        const auto& fv = mesh.faces[f];
        for (int k = 0; k < 3; ++k) {
            const int a = fv[k], b = fv[(k + 1) % 3];
            int on_edge = 0, smallest = f;
            for_each_face_on_edge(mesh, t.faces_of(a), b, [&](int g) {
                ++on_edge;
                smallest = std::min(smallest, g);
                if (g != f) {
                    if (fill) out[n] = g;
                    ++n;
                }
            });
            if (on_edge != 2 && !fill) {
                odd_edges[f] |= static_cast<unsigned char>(1u << k);
                if (smallest == f) {
                    if (on_edge == 1)
                        ++boundary_count[f];
                    else
                        ++non_manifold_count[f];
                }
            }
        }
        return n;
    };
    detail::parallel_for(nf, [&](int f) { face_degree[f] = edge_scan(f, nullptr, false); });
    if (rows == TopologyRows::All) {
        t.face_neighbour_offsets.assign(nf + 1, 0);
        for (int f = 0; f < nf; ++f)
            t.face_neighbour_offsets[f + 1] = t.face_neighbour_offsets[f] + face_degree[f];
        face_degree = {};
        t.face_neighbours.resize(t.face_neighbour_offsets[nf]);
        detail::parallel_for(nf, [&](int f) {
            int* out = t.face_neighbours.data() + t.face_neighbour_offsets[f];
            const int n = edge_scan(f, out, true);
            std::sort(out, out + n);
            // A face adjacent twice to the same face (two shared edges) appears twice: keep
            // both, the walks that use this table tolerate repeats.
        });
    }
    for (int f = 0; f < nf; ++f) {
        t.num_boundary_edges += boundary_count[f];
        t.num_non_manifold_edges += non_manifold_count[f];
    }
    // Boundary vertices: endpoints of edges with one face or more than two (found by the
    // scan above; set here, sequentially, since faces share vertices).
    for (int f = 0; f < nf; ++f) {
        if (!odd_edges[f]) continue;
        const auto& fv = mesh.faces[f];
        for (int k = 0; k < 3; ++k)
            if (odd_edges[f] >> k & 1u)
                t.vertex_on_boundary[fv[k]] = t.vertex_on_boundary[fv[(k + 1) % 3]] = 1;
    }
    if (rows == TopologyRows::VertexNeighbours) {
        release(t.vertex_face_offsets);
        release(t.vertex_faces);
    }
    return t;
}

void expect_vertex_faces(const Mesh& mesh, const MeshTopology& topology, const char* who) {
    if (topology.vertex_face_offsets.size() != mesh.positions.size() + 1)
        throw InvalidInput(std::string(who) +
                           ": the topology does not match the mesh, or has no vertices' faces");
}

namespace {

// The face areas and unit normals of make_mesh_metrics, and each face's summed edge lengths.
struct FaceMeasures {
    std::vector<double> area;
    std::vector<Eigen::Vector3d> normal;  // needed for the vertex normals only: not kept
    std::vector<double> edge_sum;
};

double face_perimeter(PositionSpan p, const std::array<int, 3>& fv) {
    return (p[fv[1]] - p[fv[0]]).norm() + (p[fv[2]] - p[fv[1]]).norm() +
           (p[fv[0]] - p[fv[2]]).norm();
}

// One face's area and unit normal (zero for a face of no area).
struct FaceMeasure {
    double area;
    Eigen::Vector3d normal;
};

FaceMeasure measure_face(const Mesh& mesh, int f) {
    const auto& p = mesh.positions;
    const auto& fv = mesh.faces[f];
    const Eigen::Vector3d cross = (p[fv[1]] - p[fv[0]]).cross(p[fv[2]] - p[fv[0]]);
    const double norm = cross.norm();
    return {0.5 * norm, norm > 0 ? Eigen::Vector3d(cross / norm) : Eigen::Vector3d::Zero()};
}

FaceMeasures measure_faces(const Mesh& mesh) {
    const int nf = mesh.num_faces();
    if (mesh.num_vertices() == 0 || nf == 0)
        throw InvalidInput("mesh metrics: the mesh has no face");
    FaceMeasures m{std::vector<double>(nf), std::vector<Eigen::Vector3d>(nf),
                   std::vector<double>(nf)};
    detail::parallel_for(nf, [&](int f) {
        const FaceMeasure face = measure_face(mesh, f);
        m.area[f] = face.area;
        m.normal[f] = face.normal;
        m.edge_sum[f] = face_perimeter(mesh.positions, mesh.faces[f]);
    });
    return m;
}

// A vertex's normal from its area-weighted sum of face normals.
Eigen::Vector3d unit_or_zero(const Eigen::Vector3d& n) {
    const double norm = n.norm();
    return norm > 0 ? Eigen::Vector3d(n / norm) : Eigen::Vector3d::Zero();
}

// The bounding box, and the mean edge length from the sum of the faces' perimeters (each
// face_perimeter, added in face order: the same value for any thread count).
void measure_extent(PositionSpan positions, int num_faces, double perimeters, MeshMetrics& m) {
    m.num_vertices = static_cast<int>(positions.size());
    m.num_faces = num_faces;
    const Eigen::AlignedBox3d box = bounding_box(positions);
    m.bbox_min = box.min();
    m.bbox_max = box.max();
    m.largest_side = (m.bbox_max - m.bbox_min).maxCoeff();
    if (!(m.largest_side > 0) || !std::isfinite(m.largest_side))
        throw InvalidInput("mesh metrics: the bounding box has zero size (all vertices coincide)");
    m.mean_edge_length = perimeters / (3.0 * num_faces);
}

double sum_in_order(const std::vector<double>& values) {
    double total = 0;
    for (double v : values) total += v;
    return total;
}

}  // namespace

MeshMetrics make_mesh_metrics(const Mesh& mesh, const MeshTopology& topology) {
    expect_vertex_faces(mesh, topology, "mesh metrics");
    FaceMeasures faces = measure_faces(mesh);
    const int nv = mesh.num_vertices();
    MeshMetrics m;
    m.vertex_normal.resize(nv);
    m.vertex_area.resize(nv);
    detail::parallel_for(nv, [&](int v) {
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        double area = 0;
        for (int f : topology.faces_of(v)) {
            n += faces.area[f] * faces.normal[f];
            area += faces.area[f];
        }
        m.vertex_normal[v] = unit_or_zero(n);
        m.vertex_area[v] = area / 3.0;
    });
    measure_extent(mesh.positions, mesh.num_faces(), sum_in_order(faces.edge_sum), m);
    m.face_area = std::move(faces.area);
    return m;
}

MeshMetrics make_mesh_extent(const Mesh& mesh) {
    MeshExtentSum sum(mesh.positions);
    sum.add(mesh.faces);
    return sum.finish();
}

void MeshExtentSum::add(const std::vector<std::array<int, 3>>& faces) {
    for (const auto& f : faces) perimeters_ += face_perimeter(positions_, f);
    faces_ += static_cast<long long>(faces.size());
}

MeshMetrics MeshExtentSum::finish() const {
    if (positions_.empty() || faces_ == 0) throw InvalidInput("mesh metrics: the mesh has no face");
    MeshMetrics m;
    measure_extent(positions_, static_cast<int>(faces_), perimeters_, m);
    return m;
}

MeshMetrics make_mesh_metrics(const Mesh& mesh) {
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    if (nv == 0 || nf == 0) throw InvalidInput("mesh metrics: the mesh has no face");
    MeshMetrics m;
    // Face by face in index order: each vertex adds its faces in the ascending order of
    // topology.faces_of, so the sums are the same bits. A face's normal is used at once and
    // never stored: a tiled run makes these metrics last, on top of everything else it holds.
    m.face_area.resize(nf);
    m.vertex_normal.assign(nv, Eigen::Vector3d::Zero());
    m.vertex_area.assign(nv, 0.0);
    double perimeters = 0;
    for (int f = 0; f < nf; ++f) {
        const FaceMeasure face = measure_face(mesh, f);
        m.face_area[f] = face.area;
        for (int v : mesh.faces[f]) {
            m.vertex_normal[v] += face.area * face.normal;
            m.vertex_area[v] += face.area;
        }
        perimeters += face_perimeter(mesh.positions, mesh.faces[f]);
    }
    for (int v = 0; v < nv; ++v) {
        m.vertex_normal[v] = unit_or_zero(m.vertex_normal[v]);
        m.vertex_area[v] /= 3.0;
    }
    measure_extent(mesh.positions, nf, perimeters, m);
    return m;
}

}  // namespace geotex
