#pragma once
/// The exact discs N_r(v) of neighbourhood.hpp for every vertex of a walk graph, found
/// cluster by cluster rather than one walk per vertex. Nearby vertices are grouped in
/// clusters of reach rho <= r/4; one walk around a cluster's centre c gives each member's
/// disc as a part every member shares (the core, N_{r-rho}(c)) and a subset of the ring
/// around it (the rest of N_{r+rho}(c)), each ring vertex's connection to the member
/// proven by a distance argument. A member where the proof fails is walked alone. Same
/// sets as DiscWalker::disc, bit for bit (docs/disc-means.md gives the proof and the cost).

#include <cstdint>
#include <vector>

#include "geometry/neighbourhood.hpp"

namespace geotex {

/// A cover of a walk graph's vertices by clusters of nearby vertices.
struct DiscClusters {
    std::vector<int> offsets{0};  ///< #clusters + 1
    std::vector<int> members;     ///< graph indices; each cluster's first member is its centre
    std::vector<double> reach;    ///< #clusters: distance from the centre to the farthest member

    int num_clusters() const { return static_cast<int>(offsets.size()) - 1; }
    int size(int k) const { return offsets[k + 1] - offsets[k]; }
};

/// Greedy cover in graph order: the first vertex in no cluster yet becomes a centre and takes
/// the vertices of its disc of radius `cluster_radius` (>= 0) that no cluster has taken.
/// Sequential and deterministic; O(#G * |N_cluster_radius|).
DiscClusters make_disc_clusters(const WalkGraph& graph, double cluster_radius);

/// The discs of one cluster's members. Member i's disc is own(i) when it has one (walked
/// alone, breadth-first order), else the core followed by the ring vertices whose bit is set
/// in mask(i), in ring order.
struct ClusterDiscs {
    std::vector<int> core;             ///< graph indices in every member's disc
    std::vector<int> ring;             ///< graph indices that may be in a member's disc
    int words = 0;                     ///< 64-bit words per member mask: ceil(#ring / 64)
    std::vector<std::uint64_t> masks;  ///< #members x words
    std::vector<int> own_offsets;      ///< #members + 1
    std::vector<int> own;              ///< graph indices

    bool has_own(int i) const { return own_offsets[i + 1] > own_offsets[i]; }
    IndexRange own_disc(int i) const {
        return {own.data() + own_offsets[i], own.data() + own_offsets[i + 1]};
    }
    const std::uint64_t* mask(int i) const {
        return masks.data() + static_cast<std::size_t>(i) * words;
    }
    /// Integers held, for memory budgets.
    std::size_t footprint() const {
        return core.size() + ring.size() + 2 * masks.size() + own.size() + own_offsets.size();
    }
};

/// Walks clusters' discs. Holds reusable buffers: make one per thread.
class ClusterDiscWalker {
  public:
    /// The graph must outlive the walker.
    explicit ClusterDiscWalker(const WalkGraph& graph);

    /// The discs of radius `radius` (> 0) of cluster k's members, into `out` (its buffers are
    /// reused). The cluster's reach must be at most radius / 4.
    void walk(const DiscClusters& clusters, int k, double radius, ClusterDiscs& out);

  private:
    const WalkGraph* graph_;
    DiscWalker alone_;                  // members whose disc the cluster's walk cannot prove
    std::vector<std::uint32_t> stamp_;  // == generation_: seen in this walk
    std::uint32_t generation_ = 0;
    std::vector<int> parent_;           // per ring position: the vertex the walk reached it from
    std::vector<int> unproven_;         // ring positions without a neighbour closer to every member
    std::vector<double> xs_, ys_, zs_;  // ring coordinates, padded to whole mask words
};

}  // namespace geotex
