#include "geometry/neighbourhood.hpp"

#include <algorithm>

namespace geotex {

DiscWalker::DiscWalker(const Mesh& mesh, const MeshTopology& topology)
    : mesh_(&mesh), topology_(&topology), stamp_(mesh.positions.size(), 0), queue_(mesh.positions.size()) {
}

std::uint32_t DiscWalker::next_generation() {
    ++generation_;
    if (generation_ >= (1u << 31)) {  // stamps would overflow: start again from clean
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        generation_ = 1;
    }
    return generation_;
}

IndexRange DiscWalker::disc(int center, double radius, int max_vertices) {
    next_generation();
    // The hot loop of the pipeline (every vertex walks its disc, twice): raw pointers, one
    // comparison for "seen in this walk" (stamp / 2 == generation), and a queue that never
    // reallocates inside the walk.
    const std::uint32_t in = 2 * generation_, gen = generation_;
    std::uint32_t* stamp = stamp_.data();
    const Eigen::Vector3d* p = mesh_->positions.data();
    const int* offsets = topology_->vertex_neighbour_offsets.data();
    const int* neighbours = topology_->vertex_neighbours.data();
    const double cx = p[center].x(), cy = p[center].y(), cz = p[center].z();
    const double r2 = radius * radius;
    int* queue = queue_.data();
    int tail = 0;
    queue[tail++] = center;
    stamp[center] = in;
    for (int head = 0; head < tail && tail < max_vertices; ++head) {
        const int v = queue[head];
        for (int k = offsets[v], end = offsets[v + 1]; k < end && tail < max_vertices; ++k) {
            const int u = neighbours[k];
            if ((stamp[u] >> 1) == gen) continue;  // already in, or known to be outside
            const double dx = p[u].x() - cx, dy = p[u].y() - cy, dz = p[u].z() - cz;
            if (dx * dx + dy * dy + dz * dz <= r2) {
                stamp[u] = in;
                queue[tail++] = u;
            } else {
                stamp[u] = in + 1;  // outside the ball whatever the path: never test it again
            }
        }
    }
    return {queue, queue + tail};
}

}  // namespace geotex
