// TriangleBvh: median splits at build, boxes refitted per set of positions, nearest-first
// distance queries. CGAL gives the point-to-triangle projection only (kernel headers, no
// AABB tree), so that distances are those its AABB_tree computed.

#include "geometry/triangle_bvh.hpp"

#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"

namespace geotex {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;

// Faces per leaf: larger leaves make a smaller tree and fewer boxes to test, smaller ones
// fewer triangles to project per leaf reached (bench/RESULTS.md, "One triangle tree for the
// depth maps").
constexpr int kLeafSize = 8;

Point to_point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

// The float at or below x (at or above, for up), so that a float box holds the doubles.
float round_down(double x) {
    if (x > std::numeric_limits<float>::max()) return std::numeric_limits<float>::max();
    if (x < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
    const float f = static_cast<float>(x);
    return f > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float round_up(double x) { return -round_down(-x); }

// The squared distance from x to the interval [lo, hi] (infinite when lo is +inf).
double gap_squared(double x, double lo, double hi) {
    const double gap = x < lo ? lo - x : (x > hi ? x - hi : 0.0);
    return gap * gap;
}

// The squared distance from q to the box at b (6 floats); infinite for an empty box.
double box_squared_distance(const Eigen::Vector3d& q, const float* b) {
    double d2 = 0;
    for (int axis = 0; axis < 3; ++axis) d2 += gap_squared(q[axis], b[axis], b[3 + axis]);
    return d2;
}

// The nodes of a tree over `count` faces (0 for none), as lay_out makes them.
std::size_t count_nodes(int count) {
    if (count <= 0) return 0;
    if (count <= kLeafSize) return 1;
    return 1 + count_nodes(count / 2) + count_nodes(count - count / 2);
}

// A coordinate as a float for choosing splits: finite, NaN as 0 (a NaN breaks the ordering
// nth_element needs).
float split_key(double x) {
    constexpr double most = std::numeric_limits<float>::max();
    return std::isnan(x) ? 0.0f : static_cast<float>(std::clamp(x, -most, most));
}

// Ranges at least this large are split into their halves' trees in parallel.
constexpr int kParallelSplit = 8192;

}  // namespace

TriangleBvh::TriangleBvh(const std::vector<Eigen::Vector3d>& positions,
                         const std::vector<std::array<int, 3>>& faces, std::vector<int> group_faces,
                         const std::vector<int>& group_offsets)
    : faces_(&faces), num_positions_(positions.size()), order_(std::move(group_faces)) {
    const int nf = static_cast<int>(faces.size()), nv = static_cast<int>(positions.size());
    if (group_offsets.empty() || group_offsets.front() != 0 ||
        group_offsets.back() != static_cast<int>(order_.size()) ||
        !std::is_sorted(group_offsets.begin(), group_offsets.end()))
        throw InvalidInput("triangle tree: the group offsets must rise from 0 to the face count");
    for (int f : order_) {
        if (f < 0 || f >= nf)
            throw InvalidInput("triangle tree: face " + std::to_string(f) + " of " +
                               std::to_string(nf) + " is out of range");
        for (int v : faces[f])
            if (v < 0 || v >= nv)
                throw InvalidInput("triangle tree: face " + std::to_string(f) +
                                   " has a corner out of range");
    }
    const int num_groups = static_cast<int>(group_offsets.size()) - 1;
    {
        // Float centroids are enough to choose splits: the boxes are computed from the
        // corners at refit, whatever the splits.
        std::vector<SplitItem> items(order_.size());
        detail::parallel_for(static_cast<int>(order_.size()), [&](int k) {
            const auto& fv = faces[order_[k]];
            const Eigen::Vector3d c =
                (positions[fv[0]] + positions[fv[1]] + positions[fv[2]]) / 3.0;
            for (int a = 0; a < 3; ++a) items[k].centroid[a] = split_key(c[a]);
            items[k].face = order_[k];
        });
        detail::parallel_for(
            num_groups,
            [&](int g) { split(items, group_offsets[g], group_offsets[g + 1] - group_offsets[g]); },
            1);
        for (std::size_t k = 0; k < items.size(); ++k) order_[k] = items[k].face;
    }
    // The shape of a tree depends on its size only (each split halves), so the nodes are laid
    // out after the splits, in one pass.
    std::size_t num_nodes = 0;
    for (int g = 0; g < num_groups; ++g)
        num_nodes += count_nodes(group_offsets[g + 1] - group_offsets[g]);
    nodes_.reserve(num_nodes);
    roots_.assign(num_groups, -1);
    for (int g = 0; g < num_groups; ++g)
        if (group_offsets[g + 1] > group_offsets[g])
            roots_[g] = lay_out(group_offsets[g], group_offsets[g + 1] - group_offsets[g]);
}

// Orders items[first, first + count) so that its first half holds the faces whose
// centroids lie lowest along the longest side of the centroids' box (ties by face id, so
// that the halves are the same sets whatever the implementation of nth_element), then
// splits each half the same way, down to leaves. The centroids travel with the faces, so
// each level is one pass over contiguous memory: reading the corners through the faces at
// every level took about 14 s on 21 million faces, mostly waiting for memory, against 6 s.
// Halving a Morton order of the centroids instead builds in one sort, but gave boxes so loose
// that queries took 1.7 times as long.
void TriangleBvh::split(std::vector<SplitItem>& items, int first, int count) {
    if (count <= kLeafSize) return;
    const auto begin = items.begin() + first, end = begin + count;
    std::array<float, 3> lo = begin->centroid, hi = lo;
    for (auto it = begin + 1; it != end; ++it)
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], it->centroid[a]);
            hi[a] = std::max(hi[a], it->centroid[a]);
        }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    const int half = count / 2;
    std::nth_element(begin, begin + half, end, [axis](const SplitItem& x, const SplitItem& y) {
        return x.centroid[axis] < y.centroid[axis] ||
               (x.centroid[axis] == y.centroid[axis] && x.face < y.face);
    });
    if (count >= kParallelSplit)
        detail::parallel_invoke([&] { split(items, first, half); },
                                [&] { split(items, first + half, count - half); });
    else {
        split(items, first, half);
        split(items, first + half, count - half);
    }
}

// Appends the nodes of the tree over order_[first, first + count) in pre-order; returns
// its root's index.
int TriangleBvh::lay_out(int first, int count) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back({first, count, 0});
    if (count > kLeafSize) {
        const int half = count / 2;
        lay_out(first, half);
        const int right = lay_out(first + half, count - half);
        nodes_[index].right = right;
    }
    return index;
}

TriangleBvh::Boxes TriangleBvh::refit(const std::vector<Eigen::Vector3d>& positions) const {
    const auto& faces = *faces_;
    if (positions.size() != num_positions_)
        throw InvalidInput("triangle tree: " + std::to_string(positions.size()) +
                           " positions for a tree built on " + std::to_string(num_positions_));
    Boxes boxes;
    boxes.degenerate.assign(faces.size(), 0);
    detail::parallel_for(static_cast<int>(order_.size()), [&](int k) {
        const auto& fv = faces[order_[k]];
        boxes.degenerate[order_[k]] =
            Triangle(to_point(positions[fv[0]]), to_point(positions[fv[1]]),
                     to_point(positions[fv[2]]))
                    .is_degenerate()
                ? 1
                : 0;
    });
    const int num_nodes = static_cast<int>(nodes_.size());
    boxes.bounds.resize(6 * static_cast<std::size_t>(num_nodes));
    constexpr float inf = std::numeric_limits<float>::infinity();
    // The leaves first, in parallel; then each inner node from its children, which come after
    // it in pre-order, so one backward pass finds them done.
    detail::parallel_for(num_nodes, [&](int i) {
        const Node& n = nodes_[i];
        if (n.count > kLeafSize) return;
        float* b = &boxes.bounds[6 * static_cast<std::size_t>(i)];
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
        Eigen::Vector3d hi = -lo;
        for (int k = n.first; k < n.first + n.count; ++k) {
            const int f = order_[k];
            if (boxes.degenerate[f]) continue;
            for (int v : faces[f]) {
                lo = lo.cwiseMin(positions[v]);
                hi = hi.cwiseMax(positions[v]);
            }
        }
        for (int a = 0; a < 3; ++a) {
            // An empty leaf keeps +inf below -inf: every query is infinitely far from it.
            b[a] = lo[a] == inf ? inf : round_down(lo[a]);
            b[3 + a] = hi[a] == -inf ? -inf : round_up(hi[a]);
        }
    });
    for (int i = num_nodes - 1; i >= 0; --i) {
        const Node& n = nodes_[i];
        if (n.count <= kLeafSize) continue;
        float* b = &boxes.bounds[6 * static_cast<std::size_t>(i)];
        const float* l = &boxes.bounds[6 * static_cast<std::size_t>(i + 1)];
        const float* r = &boxes.bounds[6 * static_cast<std::size_t>(n.right)];
        for (int a = 0; a < 3; ++a) {
            b[a] = std::min(l[a], r[a]);
            b[3 + a] = std::max(l[3 + a], r[3 + a]);
        }
    }
    return boxes;
}

int TriangleBvh::root_of(int group) const {
    if (group < 0 || group >= num_groups())
        throw InvalidInput("triangle tree: group " + std::to_string(group) + " of " +
                           std::to_string(num_groups()) + " is out of range");
    return roots_[group];
}

bool TriangleBvh::has_faces(int group, const Boxes& boxes) const {
    const int root = root_of(group);
    // An empty box (no face kept) has its least x above its greatest.
    return root >= 0 && boxes.bounds.size() == 6 * nodes_.size() &&
           boxes.bounds[6 * static_cast<std::size_t>(root)] <=
               boxes.bounds[6 * static_cast<std::size_t>(root) + 3];
}

double TriangleBvh::squared_distance(int group, const Eigen::Vector3d& q, double bound,
                                     const Boxes& boxes,
                                     const std::vector<Eigen::Vector3d>& positions) const {
    const int root = root_of(group);
    if (boxes.bounds.size() != 6 * nodes_.size() || boxes.degenerate.size() != faces_->size() ||
        positions.size() != num_positions_)
        throw InvalidInput("triangle tree: the boxes or positions are not this tree's");
    if (root < 0) return bound;
    const auto& faces = *faces_;
    const Point qp = to_point(q);
    const Kernel::Construct_projected_point_3 project;
    auto box_d2 = [&](int node) {
        return box_squared_distance(q, &boxes.bounds[6 * static_cast<std::size_t>(node)]);
    };
    double best = bound;
    // Nodes still to visit with their box's distance, the nearer child on top. Each inner
    // node visited replaces itself by at most two children, so the stack never holds more
    // than the tree's depth plus one (a tree of 2^31 faces is 30 levels deep).
    struct Entry {
        int node;
        double d2;
    };
    std::array<Entry, 64> stack;
    int top = 0;
    stack[top++] = {root, box_d2(root)};
    while (top > 0) {
        const Entry e = stack[--top];
        if (e.d2 > best) continue;  // the best so far shrank since it was pushed
        const Node& n = nodes_[e.node];
        if (n.count <= kLeafSize) {
            for (int k = n.first; k < n.first + n.count; ++k) {
                const int f = order_[k];
                if (boxes.degenerate[f]) continue;
                const auto& fv = faces[f];
                const Eigen::Vector3d &a = positions[fv[0]], &b = positions[fv[1]],
                                      &c = positions[fv[2]];
                // The triangle's own box first: projecting is the costly part of the search.
                double box_d2 = 0;
                for (int axis = 0; axis < 3; ++axis)
                    box_d2 += gap_squared(q[axis], std::min({a[axis], b[axis], c[axis]}),
                                          std::max({a[axis], b[axis], c[axis]}));
                if (box_d2 > best) continue;
                const Triangle t(to_point(a), to_point(b), to_point(c));
                best = std::min(best, CGAL::squared_distance(qp, project(t, qp)));
            }
            continue;
        }
        Entry near{e.node + 1, box_d2(e.node + 1)}, far{n.right, box_d2(n.right)};
        if (far.d2 < near.d2) std::swap(near, far);
        if (far.d2 <= best) stack[top++] = far;
        if (near.d2 <= best) stack[top++] = near;
    }
    return best;
}

}  // namespace geotex
