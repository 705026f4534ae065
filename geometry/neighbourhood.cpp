#include "geometry/neighbourhood.hpp"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"

namespace geotex {

namespace {

// Spreads the low 21 bits of x to every third bit.
std::uint64_t spread_bits(std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
}

}  // namespace

std::vector<int> morton_order(const std::vector<Eigen::Vector3d>& p,
                              const std::vector<char>& include) {
    const int n = static_cast<int>(p.size());
    if (!include.empty() && static_cast<int>(include.size()) != n)
        throw InvalidInput("Morton order: " + std::to_string(include.size()) + " flags for " +
                           std::to_string(n) + " points");
    std::vector<int> order;
    for (int i = 0; i < n; ++i)
        if (include.empty() || include[i] != 0) order.push_back(i);
    if (order.empty()) return order;
    // Keys over the bounding box of the included points; the index breaks ties, so the
    // order depends on nothing but the points.
    Eigen::Vector3d lo = p[order[0]], hi = lo;
    for (int i : order) {
        lo = lo.cwiseMin(p[i]);
        hi = hi.cwiseMax(p[i]);
    }
    const double side = (hi - lo).maxCoeff();
    const double scale = side > 0 ? ((1 << 21) - 1) / side : 0.0;
    std::vector<std::pair<std::uint64_t, int>> keyed(order.size());
    detail::parallel_for(static_cast<int>(order.size()), [&](int k) {
        const int i = order[k];
        auto cell = [&](int axis) {
            const double q = (p[i][axis] - lo[axis]) * scale;
            return static_cast<std::uint64_t>(q >= 0 ? q : 0.0);  // NaN-safe: 0
        };
        keyed[k] = {spread_bits(cell(0)) | spread_bits(cell(1)) << 1 | spread_bits(cell(2)) << 2,
                    i};
    });
    // Keys are unique pairs: either sort gives the same order.
    if (detail::serial())
        std::sort(keyed.begin(), keyed.end());
    else
        tbb::parallel_sort(keyed.begin(), keyed.end());
    for (std::size_t k = 0; k < keyed.size(); ++k) order[k] = keyed[k].second;
    return order;
}

WalkGraph make_walk_graph(const Mesh& mesh, const MeshTopology& topology,
                          const std::vector<char>& include) {
    const int nv = mesh.num_vertices();
    if (!include.empty() && static_cast<int>(include.size()) != nv)
        throw InvalidInput("walk graph: " + std::to_string(include.size()) + " vertex flags for " +
                           std::to_string(nv) + " vertices");
    WalkGraph g;
    g.mesh_vertex = morton_order(mesh.positions, include);
    const int ng = g.num_vertices();
    if (ng == 0) {
        g.graph_vertex.assign(nv, -1);
        g.neighbour_offsets.assign(1, 0);
        return g;
    }
    const std::vector<Eigen::Vector3d>& p = mesh.positions;
    g.graph_vertex.assign(nv, -1);
    for (int i = 0; i < ng; ++i) g.graph_vertex[g.mesh_vertex[i]] = i;
    g.positions.resize(ng);
    g.neighbour_offsets.assign(ng + 1, 0);
    for (int i = 0; i < ng; ++i) {
        const int v = g.mesh_vertex[i];
        g.positions[i] = p[v];
        g.neighbour_offsets[i + 1] = g.neighbour_offsets[i] + topology.neighbours(v).size();
    }
    g.neighbours.resize(g.neighbour_offsets[ng]);
    bool closed = true;
    for (int i = 0; i < ng; ++i) {
        int* out = g.neighbours.data() + g.neighbour_offsets[i];
        for (int u : topology.neighbours(g.mesh_vertex[i])) {
            if (g.graph_vertex[u] < 0) closed = false;
            *out++ = g.graph_vertex[u];
        }
    }
    if (!closed)
        throw InvalidInput(
            "walk graph: the included vertices have neighbours that are not included; "
            "include whole connected components");
    return g;
}

DiscWalker::DiscWalker(const Mesh& mesh, const MeshTopology& topology)
    : positions_(mesh.positions.data()),
      offsets_(topology.vertex_neighbour_offsets.data()),
      neighbours_(topology.vertex_neighbours.data()),
      stamp_(mesh.positions.size(), 0),
      queue_(mesh.positions.size()) {}

DiscWalker::DiscWalker(const WalkGraph& graph)
    : positions_(graph.positions.data()),
      offsets_(graph.neighbour_offsets.data()),
      neighbours_(graph.neighbours.data()),
      stamp_(graph.positions.size(), 0),
      queue_(graph.positions.size()) {}

std::uint32_t DiscWalker::next_generation() {
    ++generation_;
    if (generation_ >= (1u << 31)) {  // stamps would overflow: start again from clean
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        generation_ = 1;
    }
    return generation_;
}

namespace {

// The hot loop of the pipeline (every vertex walks its disc, twice): raw pointers, one
// comparison for "seen in this walk" (stamp / 2 == generation), and a queue that never
// reallocates inside the walk. The cap's test is compiled out of uncapped walks.
template <bool kCapped>
int walk_disc(const Eigen::Vector3d* p, const int* offsets, const int* neighbours,
              std::uint32_t* stamp, std::uint32_t gen, int* queue, int center, double radius,
              int max_vertices) {
    const std::uint32_t in = 2 * gen, out = in + 1;
    const double cx = p[center].x(), cy = p[center].y(), cz = p[center].z();
    const double r2 = radius * radius;
    int tail = 0;
    queue[tail++] = center;
    stamp[center] = in;
    for (int head = 0; head < tail && (!kCapped || tail < max_vertices); ++head) {
        const int v = queue[head];
        for (int k = offsets[v], end = offsets[v + 1]; k < end && (!kCapped || tail < max_vertices);
             ++k) {
            const int u = neighbours[k];
            if ((stamp[u] >> 1) == gen) continue;  // already in, or known to be outside
            const double dx = p[u].x() - cx, dy = p[u].y() - cy, dz = p[u].z() - cz;
            if (dx * dx + dy * dy + dz * dz <= r2) {
                stamp[u] = in;
                queue[tail++] = u;
            } else {
                stamp[u] = out;  // outside the ball whatever the path: never test it again
            }
        }
    }
    return tail;
}

}  // namespace

IndexRange DiscWalker::disc(int center, double radius, int max_vertices) {
    const std::uint32_t gen = next_generation();
    const int tail = max_vertices < std::numeric_limits<int>::max()
                         ? walk_disc<true>(positions_, offsets_, neighbours_, stamp_.data(), gen,
                                           queue_.data(), center, radius, max_vertices)
                         : walk_disc<false>(positions_, offsets_, neighbours_, stamp_.data(), gen,
                                            queue_.data(), center, radius, max_vertices);
    return {queue_.data(), queue_.data() + tail};
}

}  // namespace geotex
