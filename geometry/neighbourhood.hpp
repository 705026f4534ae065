#pragma once
/// The geodesic disc N_r(v) of the paper (§3.1): the connected part of the mesh around v
/// that lies inside the ball of radius r centred at v. Unlike a Euclidean ball query, the
/// walk never jumps across a thin gap to another sheet of the surface.

#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/mesh.hpp"
#include "geometry/topology.hpp"

namespace geotex {

/// Some vertices of a mesh renumbered along a space-filling curve (Morton order), with their
/// adjacency, so that the vertices of a disc, and the discs of consecutive centres, lie close
/// together in memory: the walks of the exact disc means are bound by memory latency on
/// meshes numbered otherwise (an icosphere's vertices are numbered by subdivision level).
/// Each row keeps the order of the mesh's row (ascending mesh index), so a walk over the
/// graph visits the same vertices in the same order as a walk over the mesh, and sums over
/// its discs are bit for bit the same.
struct WalkGraph {
    std::vector<int> mesh_vertex;            ///< #G, mesh index of each graph vertex
    std::vector<int> graph_vertex;           ///< #V, graph index of each mesh vertex, or -1
    std::vector<Eigen::Vector3d> positions;  ///< #G
    std::vector<int> neighbour_offsets;      ///< #G + 1
    std::vector<int> neighbours;             ///< graph indices, rows in mesh-row order

    int num_vertices() const { return static_cast<int>(mesh_vertex.size()); }
};

/// The indices i flagged in `include` (#positions; empty: all) ordered along a Morton curve
/// over their bounding box, ties by index, so that consecutive ones are close in space: the
/// order of the walk graph, and of the depth map's queries. Deterministic; parallel sort.
/// Throws InvalidInput when `include` has the wrong size.
std::vector<int> morton_order(const std::vector<Eigen::Vector3d>& positions,
                              const std::vector<char>& include = {});

/// The walk graph of the vertices flagged in `include` (#V; empty: all). The flagged set
/// must be closed under adjacency (whole connected components). Deterministic;
/// O(#G log #G). Throws InvalidInput when `include` has the wrong size or is not closed.
WalkGraph make_walk_graph(const Mesh& mesh, const MeshTopology& topology,
                          const std::vector<char>& include = {});

/// Breadth-first walk over mesh edges that stops at the sphere of radius r. Holds reusable
/// buffers (visit stamps, queue): make one per thread and reuse it; construction is O(#V),
/// each walk is O(size of the disc).
class DiscWalker {
  public:
    DiscWalker(const Mesh& mesh, const MeshTopology& topology);
    /// Walks over a walk graph: vertices (centres and results) are graph indices. The graph
    /// must outlive the walker.
    explicit DiscWalker(const WalkGraph& graph);

    /// Vertices of N_r(center) in breadth-first order, `center` first. A vertex is in the
    /// disc when its distance to the centre is <= radius and an edge path of such vertices
    /// joins it to the centre. The range is valid until the next call.
    /// With `max_vertices`, the walk stops once it holds that many: the disc is then the
    /// max_vertices vertices nearest the centre in breadth-first (edge-hop) order, which
    /// bounds the cost on fine meshes.
    IndexRange disc(int center, double radius, int max_vertices = std::numeric_limits<int>::max());

    /// True if `v` belongs to the disc of the last call to disc().
    bool contains(int v) const { return stamp_[v] == 2 * generation_; }

    /// The first vertex of N_r(center) in breadth-first order (the order of disc()) for which
    /// pred(vertex) is true, or -1 if there is none. Stops at that vertex, so a test that
    /// usually succeeds near the centre costs a ring or two instead of the whole disc.
    /// Invalidates the last disc().
    template <class Pred>
    int find_in_disc(int center, double radius, Pred&& pred);

  private:
    std::uint32_t next_generation();

    const Eigen::Vector3d* positions_;
    const int* offsets_;  // #V + 1
    const int* neighbours_;
    std::vector<std::uint32_t> stamp_;  // 2g: in disc g; 2g+1: visited in walk g, outside
    std::uint32_t generation_ = 0;
    std::vector<int> queue_;  // #V, breadth-first queue; the last disc is its first part
};

template <class Pred>
int DiscWalker::find_in_disc(int center, double radius, Pred&& pred) {
    const std::uint32_t gen = next_generation(), in = 2 * gen;
    std::uint32_t* stamp = stamp_.data();
    const Eigen::Vector3d* p = positions_;
    const double cx = p[center].x(), cy = p[center].y(), cz = p[center].z();
    const double r2 = radius * radius;
    if (pred(center)) return center;
    int* queue = queue_.data();
    int tail = 0;
    queue[tail++] = center;
    stamp[center] = in;
    for (int head = 0; head < tail; ++head) {
        const int v = queue[head];
        for (int k = offsets_[v], end = offsets_[v + 1]; k < end; ++k) {
            const int u = neighbours_[k];
            if ((stamp[u] >> 1) == gen) continue;
            const double dx = p[u].x() - cx, dy = p[u].y() - cy, dz = p[u].z() - cz;
            if (dx * dx + dy * dy + dz * dz <= r2) {
                if (pred(u)) return u;
                stamp[u] = in;
                queue[tail++] = u;
            } else {
                stamp[u] = in + 1;
            }
        }
    }
    return -1;
}

}  // namespace geotex
