// make_depth_map: the oriented rule of paper eq. 2 and the distance to the smoothed surface.
// The only CGAL user of the pipeline's hot path (AABB tree); keep CGAL out of headers.

#include "geometry/depth_map.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <memory>
#include <string>

#include "geometry/detail/parallel.hpp"
#include "geometry/detail/union_find.hpp"
#include "geometry/errors.hpp"

namespace geotex {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point to_point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

}  // namespace

DepthMap make_depth_map(const Mesh& mesh, const std::vector<Eigen::Vector3d>& vertex_normal,
                        const SmoothedSurface& smoothed, DetailOrientation orientation) {
    const int nv = mesh.num_vertices();
    const int nf = mesh.num_faces();
    if (static_cast<int>(smoothed.positions.size()) != nv ||
        static_cast<int>(vertex_normal.size()) != nv)
        throw InvalidInput(
            "depth map: smoothed positions and normals must have one row per vertex (" +
            std::to_string(nv) + ")");
    const double sign = orientation == DetailOrientation::Positive ? 1.0 : -1.0;

    // Oriented smoothed surface: a vertex moves to v_s only where it stands out of the
    // smoothed surface on the chosen side (eq. 2 and its mirror).
    std::vector<Eigen::Vector3d> oriented(nv);
    std::vector<char> moved(nv, 0);
    detail::parallel_for(nv, [&](int v) {
        const Eigen::Vector3d& vo = mesh.positions[v];
        const Eigen::Vector3d& vs = smoothed.positions[v];
        const bool stands_out = sign * (vo - vs).dot(vertex_normal[v]) > 0;
        oriented[v] = stands_out ? vs : vo;
        moved[v] = stands_out ? 1 : 0;
    });

    DepthMap d;
    d.orientation = orientation;
    d.vertex_depth.assign(nv, 0.0);
    d.face_depth.assign(nf, 0.0);
    for (char m : moved) d.num_moved_vertices += m;

    if (d.num_moved_vertices > 0) {
        // One tree per connected component: the depth of a vertex is measured to its own
        // part of the smoothed surface, never across the gap to another part (two fragments
        // of a scan a millimetre apart, the two sides of a thin sheet that do not connect).
        detail::UnionFind parts(nv);
        for (const auto& f : mesh.faces) {
            parts.unite(f[0], f[1]);
            parts.unite(f[0], f[2]);
        }
        std::vector<int> component(nv, -1);  // numbered by first vertex
        int num_components = 0;
        for (int v = 0; v < nv; ++v) {
            const int root = parts.find(v);
            component[v] = root == v ? num_components++ : component[root];
        }
        // Each component's triangles in face order, sized first and filled in parallel (on
        // level 9 of sphere-1 they take 380 MB: growing them by doubling cost a second of copies).
        auto triangle_of = [&](int f) {
            const auto& fv = mesh.faces[f];
            return Triangle(to_point(oriented[fv[0]]), to_point(oriented[fv[1]]), to_point(oriented[fv[2]]));
        };
        std::vector<int> slot(nf, -1);  // index in its component's triangles; -1: left out
        // A degenerate triangle adds no surface (its points lie on its neighbours' edges) and
        // CGAL's triangle distance expects a proper triangle.
        detail::parallel_for(nf, [&](int f) { slot[f] = triangle_of(f).is_degenerate() ? -1 : 0; });
        std::vector<int> component_size(num_components, 0);
        for (int f = 0; f < nf; ++f)
            if (slot[f] == 0) slot[f] = component_size[component[mesh.faces[f][0]]]++;
        std::vector<std::vector<Triangle>> triangles(num_components);
        for (int c = 0; c < num_components; ++c) triangles[c].resize(component_size[c]);
        detail::parallel_for(nf, [&](int f) {
            if (slot[f] >= 0) triangles[component[mesh.faces[f][0]]][slot[f]] = triangle_of(f);
        });
        std::vector<int>().swap(slot);
        std::vector<std::unique_ptr<Tree>> trees(num_components);
        for (int c = 0; c < num_components; ++c) {
            if (triangles[c].empty()) continue;
            trees[c] = std::make_unique<Tree>(triangles[c].cbegin(), triangles[c].cend());
            trees[c]->build();
            trees[c]->do_not_accelerate_distance_queries();  // every query below brings a hint
        }
        // A vertex that stayed has depth 0 exactly: it is a vertex of the smoothed mesh. A
        // moved vertex starts its search from its own smoothed position, a point of the
        // surface close to the answer.
        detail::parallel_for(
            nv,
            [&](int v) {
                const Tree* tree = trees[component[v]].get();
                if (!moved[v] || !tree) return;
                const Point q = to_point(mesh.positions[v]);
                d.vertex_depth[v] = std::sqrt(tree->squared_distance(q, to_point(oriented[v])));
            },
            256);
    }
    for (double x : d.vertex_depth) d.max_depth = std::max(d.max_depth, x);
    detail::parallel_for(nf, [&](int f) {
        const auto& fv = mesh.faces[f];
        d.face_depth[f] =
            (d.vertex_depth[fv[0]] + d.vertex_depth[fv[1]] + d.vertex_depth[fv[2]]) / 3.0;
    });
    return d;
}

}  // namespace geotex
