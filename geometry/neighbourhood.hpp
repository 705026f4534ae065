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

/// Breadth-first walk over mesh edges that stops at the sphere of radius r. Holds reusable
/// buffers (visit stamps, queue): make one per thread and reuse it; construction is O(#V),
/// each walk is O(size of the disc).
class DiscWalker {
public:
    DiscWalker(const Mesh& mesh, const MeshTopology& topology);

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

    const Mesh* mesh_;
    const MeshTopology* topology_;
    std::vector<std::uint32_t> stamp_;  // 2g: in disc g; 2g+1: visited in walk g, outside
    std::uint32_t generation_ = 0;
    std::vector<int> queue_;  // #V, breadth-first queue; the last disc is its first part
};

template <class Pred>
int DiscWalker::find_in_disc(int center, double radius, Pred&& pred) {
    const std::uint32_t gen = next_generation(), in = 2 * gen;
    std::uint32_t* stamp = stamp_.data();
    const Eigen::Vector3d* p = mesh_->positions.data();
    const int* offsets = topology_->vertex_neighbour_offsets.data();
    const int* neighbours = topology_->vertex_neighbours.data();
    const Eigen::Vector3d c = p[center];
    const double r2 = radius * radius;
    if (pred(center)) return center;
    int* queue = queue_.data();
    int tail = 0;
    queue[tail++] = center;
    stamp[center] = in;
    for (int head = 0; head < tail; ++head) {
        const int v = queue[head];
        for (int k = offsets[v], end = offsets[v + 1]; k < end; ++k) {
            const int u = neighbours[k];
            if ((stamp[u] >> 1) == gen) continue;
            const double dx = p[u].x() - c.x(), dy = p[u].y() - c.y(), dz = p[u].z() - c.z();
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
