// make_depth_map: the oriented rule of paper eq. 2 and the distance to the smoothed surface.
// The only CGAL user of the pipeline's hot path (AABB tree); keep CGAL out of headers.

#include "geometry/depth_map.hpp"

#include <CGAL/AABB_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/neighbourhood.hpp"

namespace geotex {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;

Point to_point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

// The tree's primitives are face ids, and their triangles are made from the oriented
// positions when the tree asks: a stored triangle (72 bytes a face, beside the tree's 64)
// was the largest buffer of the pipeline at its peak (bench/RESULTS.md, issue 21). The
// reference point is the triangle's first vertex, as CGAL's triangle primitive's, so that
// the tree, and each distance, are those of the stored triangles.
struct OrientedFaces {
    const Mesh* mesh = nullptr;
    const std::vector<Eigen::Vector3d>* oriented = nullptr;

    Triangle triangle(int f) const {
        const auto& fv = mesh->faces[f];
        return Triangle(to_point((*oriented)[fv[0]]), to_point((*oriented)[fv[1]]),
                        to_point((*oriented)[fv[2]]));
    }
};
struct TriangleMap {
    using key_type = int;
    using value_type = Triangle;
    using reference = Triangle;
    using category = boost::readable_property_map_tag;
    OrientedFaces faces;
    friend Triangle get(const TriangleMap& m, int f) { return m.faces.triangle(f); }
};
struct FirstVertexMap {
    using key_type = int;
    using value_type = Point;
    using reference = Point;
    using category = boost::readable_property_map_tag;
    OrientedFaces faces;
    friend Point get(const FirstVertexMap& m, int f) {
        return to_point((*m.faces.oriented)[m.faces.mesh->faces[f][0]]);
    }
};
using Primitive = CGAL::AABB_primitive<int, TriangleMap, FirstVertexMap,
                                       CGAL::Tag_true /* maps in the tree */, CGAL::Tag_false>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

// CGAL builds a tree on one thread (0.13 s for the 327,680 triangles of sphere-1 level 7).
// A component with at least this many triangles is cut in two halves at the median of the
// triangles' centroids along its longest axis (the split the tree would make first), and
// the halves' trees are built in parallel. The cut depends on the mesh only.
constexpr std::size_t kSplitTriangles = 65536;

// The trees of one connected component: one, or two halves.
struct ComponentTrees {
    std::unique_ptr<Tree> tree[2];
    CGAL::Bbox_3 box[2];

    // The squared distance from q to the component's triangles, starting from `hint`, a
    // point of the surface: each half is asked in turn, nearer box first, with the best point
    // so far as its hint. Min over all triangles either way, so the same distance as one tree.
    double squared_distance(const Point& q, const Point& hint) const {
        if (!tree[1]) return tree[0]->squared_distance(q, hint);
        auto box_distance = [&](const CGAL::Bbox_3& b) {
            double d2 = 0;
            for (int i = 0; i < 3; ++i) {
                const double x = q[i], gap = x < b.min(i) ? b.min(i) - x
                                                          : (x > b.max(i) ? x - b.max(i) : 0.0);
                d2 += gap * gap;
            }
            return d2;
        };
        const int first = box_distance(box[1]) < box_distance(box[0]) ? 1 : 0;
        Point best = tree[first]->closest_point(q, hint);
        best = tree[1 - first]->closest_point(q, best);
        return CGAL::squared_distance(q, best);
    }
};

// Builds the trees of the faces `triangles` (emptied): one tree, or two halves built in
// parallel.
void build_trees(std::vector<int>& triangles, const OrientedFaces& faces, ComponentTrees& out) {
    auto build = [&](std::vector<int>& t, std::unique_ptr<Tree>& tree, CGAL::Bbox_3& box) {
        tree =
            std::make_unique<Tree>(t.cbegin(), t.cend(), TriangleMap{faces}, FirstVertexMap{faces});
        tree->build();
        tree->do_not_accelerate_distance_queries();  // every query brings a hint
        box = tree->bbox();
        std::vector<int>().swap(t);  // the primitives hold the ids
    };
    const std::size_t n = triangles.size();
    if (n < kSplitTriangles) {
        build(triangles, out.tree[0], out.box[0]);
        return;
    }
    CGAL::Bbox_3 all;
    for (int f : triangles) all += faces.triangle(f).bbox();
    int axis = 0;
    for (int i = 1; i < 3; ++i)
        if (all.max(i) - all.min(i) > all.max(axis) - all.min(axis)) axis = i;
    std::vector<double> key(n);
    detail::parallel_for(static_cast<int>(n), [&](int i) {
        const Triangle t = faces.triangle(triangles[i]);
        key[i] = t[0][axis] + t[1][axis] + t[2][axis];
    });
    // The lower half: keys below the median, then ties with it in face order until it holds
    // n/2 triangles; each half keeps face order.
    std::vector<double> sorted_keys = key;
    const auto mid = sorted_keys.begin() + static_cast<std::ptrdiff_t>(n / 2);
    std::nth_element(sorted_keys.begin(), mid, sorted_keys.end());
    const double median = *mid;
    std::size_t below = 0;
    for (double k : key) below += k < median;
    std::vector<std::int32_t> slot(
        n);  // >= 0: index in the lower half; < 0: -1 - index in the upper
    std::size_t lower = 0, upper = 0, ties = n / 2 - below;
    for (std::size_t i = 0; i < n; ++i) {
        const bool low = key[i] < median || (key[i] == median && ties > 0 && ties--);
        slot[i] =
            low ? static_cast<std::int32_t>(lower++) : -1 - static_cast<std::int32_t>(upper++);
    }
    std::vector<int> halves[2];
    halves[0].resize(lower);
    halves[1].resize(upper);
    detail::parallel_for(static_cast<int>(n), [&](int i) {
        if (slot[i] >= 0)
            halves[0][slot[i]] = triangles[i];
        else
            halves[1][-1 - slot[i]] = triangles[i];
    });
    std::vector<int>().swap(triangles);
    detail::parallel_invoke([&] { build(halves[0], out.tree[0], out.box[0]); },
                            [&] { build(halves[1], out.tree[1], out.box[1]); });
}

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
        const VertexComponents parts = vertex_components(mesh);
        const std::vector<int>& component = parts.component;
        const int num_components = parts.num_components;
        // Each component's faces in face order (ids: the tree makes their triangles from
        // `oriented` when it asks).
        const OrientedFaces faces{&mesh, &oriented};
        // A degenerate triangle adds no surface (its points lie on its neighbours' edges) and
        // CGAL's triangle distance expects a proper triangle.
        std::vector<char> kept(nf, 0);
        detail::parallel_for(nf,
                             [&](int f) { kept[f] = faces.triangle(f).is_degenerate() ? 0 : 1; });
        std::vector<int> component_size(num_components, 0);
        for (int f = 0; f < nf; ++f)
            if (kept[f]) ++component_size[component[mesh.faces[f][0]]];
        std::vector<std::vector<int>> triangles(num_components);
        for (int c = 0; c < num_components; ++c) triangles[c].reserve(component_size[c]);
        for (int f = 0; f < nf; ++f)
            if (kept[f]) triangles[component[mesh.faces[f][0]]].push_back(f);
        std::vector<char>().swap(kept);
        std::vector<ComponentTrees> trees(num_components);
        for (int c = 0; c < num_components; ++c)
            if (!triangles[c].empty()) build_trees(triangles[c], faces, trees[c]);
        // A vertex that stayed has depth 0 exactly: it is a vertex of the smoothed mesh. A
        // moved vertex starts its search from its own smoothed position, a point of the
        // surface close to the answer.
        // Queries along a Morton curve: consecutive ones walk the same branches of the trees.
        const std::vector<int> query_order = morton_order(mesh.positions, moved);
        detail::parallel_for(
            static_cast<int>(query_order.size()),
            [&](int i) {
                const int v = query_order[i];
                const ComponentTrees& tree = trees[component[v]];
                if (!tree.tree[0]) return;
                const Point q = to_point(mesh.positions[v]);
                d.vertex_depth[v] = std::sqrt(tree.squared_distance(q, to_point(oriented[v])));
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
