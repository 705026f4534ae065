// make_depth_map and DepthMapper: the oriented rule of paper eq. 2 and the distance to the
// smoothed surface, measured with one triangle tree refitted to each surface.

#include "geometry/depth_map.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/neighbourhood.hpp"

namespace geotex {

namespace {

// The faces of each connected component, in face order: the groups of the triangle tree.
// Split on the mesh's own positions: a smoothed surface moves each vertex a little (at most
// its depth), so the refitted boxes stay about as tight as the mesh's.
TriangleBvh make_component_trees(const Mesh& mesh, const VertexComponents& components) {
    const std::vector<int>& component = components.component;
    const int num_components = components.num_components;
    std::vector<int> offsets(num_components + 1, 0);
    for (const auto& fv : mesh.faces) ++offsets[component[fv[0]] + 1];
    for (int c = 0; c < num_components; ++c) offsets[c + 1] += offsets[c];
    std::vector<int> faces(mesh.faces.size());
    std::vector<int> next(offsets.begin(), offsets.end() - 1);
    for (int f = 0; f < mesh.num_faces(); ++f) faces[next[component[mesh.faces[f][0]]]++] = f;
    return TriangleBvh(mesh.positions, mesh.faces, std::move(faces), offsets);
}

}  // namespace

// One tree per connected component: the depth of a vertex is measured to its own part of the
// smoothed surface, never across the gap to another part (two fragments of a scan a
// millimetre apart, the two sides of a thin sheet that do not connect). Queries go along a
// Morton curve: consecutive ones walk the same branches of the tree.
DepthMapper::DepthMapper(const Mesh& mesh)
    : mesh_(&mesh),
      components_(vertex_components(mesh)),
      tree_(make_component_trees(mesh, components_)),
      query_order_(morton_order(mesh.positions)) {}

namespace {

VertexComponents checked(const Mesh& mesh, VertexComponents components) {
    if (static_cast<int>(components.component.size()) != mesh.num_vertices())
        throw InvalidInput("depth map: " + std::to_string(components.component.size()) +
                           " component ids for " + std::to_string(mesh.num_vertices()) +
                           " vertices");
    for (int c : components.component)
        if (c < 0 || c >= components.num_components)
            throw InvalidInput("depth map: a component id is not in [0, " +
                               std::to_string(components.num_components) + ")");
    return components;
}

}  // namespace

DepthMapper::DepthMapper(const Mesh& mesh, VertexComponents components)
    : mesh_(&mesh),
      components_(checked(mesh, std::move(components))),
      tree_(make_component_trees(mesh, components_)),
      query_order_(morton_order(mesh.positions)) {}

DepthMap DepthMapper::map(const std::vector<Eigen::Vector3d>& vertex_normal,
                          const SmoothedSurface& smoothed, DetailOrientation orientation) const {
    const Mesh& mesh = *mesh_;
    const int nv = mesh.num_vertices();
    const int nf = mesh.num_faces();
    if (static_cast<int>(smoothed.positions.size()) != nv ||
        static_cast<int>(vertex_normal.size()) != nv)
        throw InvalidInput(
            "depth map: smoothed positions and normals must have one row per vertex (" +
            std::to_string(nv) + ")");
    // Oriented smoothed surface: a vertex moves to v_s only where it stands out of the
    // smoothed surface on the chosen side (eq. 2 and its mirror).
    std::vector<Eigen::Vector3d> oriented(nv);
    std::vector<char> moved(nv, 0);
    detail::parallel_for(nv, [&](int v) {
        const Eigen::Vector3d& vo = mesh.positions[v];
        const Eigen::Vector3d& vs = smoothed.positions[v];
        const bool out = stands_out(vo, vs, vertex_normal[v], orientation);
        oriented[v] = out ? vs : vo;
        moved[v] = out ? 1 : 0;
    });

    DepthMap d;
    d.orientation = orientation;
    d.vertex_depth.assign(nv, 0.0);
    d.face_depth.assign(nf, 0.0);
    for (char m : moved) d.num_moved_vertices += m;

    if (d.num_moved_vertices > 0) {
        const TriangleBvh::Boxes boxes = tree_.refit(oriented);
        // A vertex that stayed has depth 0 exactly: it is a vertex of the smoothed mesh. A
        // moved vertex starts its search from its own smoothed position, a point of the
        // surface close to the answer.
        std::vector<int> queries;
        queries.reserve(d.num_moved_vertices);
        for (int v : query_order_)
            if (moved[v]) queries.push_back(v);
        detail::parallel_for(
            static_cast<int>(queries.size()),
            [&](int i) {
                const int v = queries[i];
                // A component whose triangles are all degenerate has no surface to measure to.
                if (!tree_.has_faces(components_.component[v], boxes)) return;
                const Eigen::Vector3d& q = mesh.positions[v];
                const Eigen::Vector3d gap = q - oriented[v];
                // Summed as CGAL sums a squared distance, so that a vertex with no closer
                // triangle gets the bits it had when the search ran in CGAL's tree.
                const double bound = gap.x() * gap.x() + gap.y() * gap.y() + gap.z() * gap.z();
                d.vertex_depth[v] = std::sqrt(
                    tree_.squared_distance(components_.component[v], q, bound, boxes, oriented));
            },
            256);
    }
    set_face_depths(mesh, d);
    return d;
}

void set_face_depths(const Mesh& mesh, DepthMap& d) {
    d.max_depth = 0;
    for (double x : d.vertex_depth) d.max_depth = std::max(d.max_depth, x);
    d.face_depth.resize(static_cast<std::size_t>(mesh.num_faces()));
    detail::parallel_for(mesh.num_faces(), [&](int f) {
        const auto& fv = mesh.faces[f];
        d.face_depth[f] =
            (d.vertex_depth[fv[0]] + d.vertex_depth[fv[1]] + d.vertex_depth[fv[2]]) / 3.0;
    });
}

DepthMap make_depth_map(const Mesh& mesh, const std::vector<Eigen::Vector3d>& vertex_normal,
                        const SmoothedSurface& smoothed, DetailOrientation orientation) {
    return DepthMapper(mesh).map(vertex_normal, smoothed, orientation);
}

}  // namespace geotex
