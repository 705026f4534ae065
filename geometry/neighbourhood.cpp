#include "geometry/neighbourhood.hpp"

#include <algorithm>

namespace geotex {

DiscWalker::DiscWalker(const Mesh& mesh, const MeshTopology& topology)
    : mesh_(&mesh), topology_(&topology), stamp_(mesh.positions.size(), 0) {
    queue_.reserve(1024);
}

const std::vector<int>& DiscWalker::disc(int center, double radius) {
    ++generation_;
    if (generation_ >= (1u << 31)) {  // stamps would overflow: start again from clean
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        generation_ = 1;
    }
    const std::uint32_t in = 2 * generation_, out = in + 1;
    const auto& p = mesh_->positions;
    const Eigen::Vector3d c = p[center];
    const double r2 = radius * radius;
    queue_.clear();
    queue_.push_back(center);
    stamp_[center] = in;
    for (std::size_t head = 0; head < queue_.size(); ++head) {
        for (int u : topology_->neighbours(queue_[head])) {
            if (stamp_[u] == in || stamp_[u] == out) continue;
            if ((p[u] - c).squaredNorm() <= r2) {
                stamp_[u] = in;
                queue_.push_back(u);
            } else {
                stamp_[u] = out;  // outside the ball whatever the path: never test it again
            }
        }
    }
    return queue_;
}

}  // namespace geotex
