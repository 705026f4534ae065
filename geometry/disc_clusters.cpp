// Exact discs of clustered vertices from one walk per cluster.
//
// Why the result is N_r(v) exactly, for a member v of a cluster with centre c and reach
// rho (|v - c| <= rho <= r/2):
// - Every vertex of N_r(v) lies within r + rho of c and is joined to v, hence to c, inside
//   that ball: N_r(v) is in R = N_{r+rho}(c), the walk around the cluster.
// - The core N_{r-rho}(c) lies within r of v and is joined to c inside that ball; v is in
//   it (the member check below). So the core is in N_r(v).
// - A ring vertex u (in R, not in the core) within r of v belongs to N_r(v) if it has a
//   neighbour closer to v: that neighbour is within r of v, so in R, and repeating the step
//   descends strictly until it reaches the core or v. "Closer to every point within rho of
//   c" is linear in the point: |w - c|^2 - |u - c|^2 + 2 rho |w - u| < 0 suffices, checked
//   once per cluster; a ring vertex without such a neighbour is checked against the member
//   itself, and a member where that fails too is walked alone.
// The inequalities carry a relative margin of 1e-9 (the radii, the linear bound), far above
// the rounding of squared distances, so the sets are those of DiscWalker::disc, which tests
// the same squared distances in the same arithmetic.

#include "geometry/disc_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace geotex {

namespace {

constexpr double kMargin = 1e-9;

double squared_distance(const Eigen::Vector3d& a, double cx, double cy, double cz) {
    const double dx = a.x() - cx, dy = a.y() - cy, dz = a.z() - cz;
    return dx * dx + dy * dy + dz * dz;
}

// Bit b set where point b of the 64 (x, y, z) is within sqrt(r2) of (vx, vy, vz), by the
// squared distance of squared_distance(). Two points per instruction where SSE2 is there
// (every x86-64): the compiler does not vectorise the packing of comparisons into bits. The
// same operations in the same order, so the same bits either way.
std::uint64_t inside_bits(const double* x, const double* y, const double* z, double vx, double vy,
                          double vz, double r2) {
    std::uint64_t bits = 0;
#if defined(__SSE2__)
    const __m128d px = _mm_set1_pd(vx), py = _mm_set1_pd(vy), pz = _mm_set1_pd(vz),
                  limit = _mm_set1_pd(r2);
    for (int b = 0; b < 64; b += 2) {
        const __m128d dx = _mm_sub_pd(_mm_loadu_pd(x + b), px);
        const __m128d dy = _mm_sub_pd(_mm_loadu_pd(y + b), py);
        const __m128d dz = _mm_sub_pd(_mm_loadu_pd(z + b), pz);
        const __m128d d2 =
            _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz));
        bits |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_cmple_pd(d2, limit))) << b;
    }
#else
    for (int b = 0; b < 64; ++b) {
        const double dx = x[b] - vx, dy = y[b] - vy, dz = z[b] - vz;
        bits |= static_cast<std::uint64_t>(dx * dx + dy * dy + dz * dz <= r2) << b;
    }
#endif
    return bits;
}

}  // namespace

DiscClusters make_disc_clusters(const WalkGraph& graph, double cluster_radius) {
    const int ng = graph.num_vertices();
    DiscClusters clusters;
    clusters.members.reserve(ng);
    std::vector<char> taken(ng, 0);
    DiscWalker walker(graph);
    for (int c = 0; c < ng; ++c) {
        if (taken[c]) continue;
        const Eigen::Vector3d& pc = graph.positions[c];
        double reach2 = 0;
        for (int u : walker.disc(c, cluster_radius)) {  // c first
            if (taken[u]) continue;
            taken[u] = 1;
            clusters.members.push_back(u);
            reach2 = std::max(reach2, (graph.positions[u] - pc).squaredNorm());
        }
        clusters.offsets.push_back(static_cast<int>(clusters.members.size()));
        clusters.reach.push_back(std::sqrt(reach2));
    }
    return clusters;
}

ClusterDiscWalker::ClusterDiscWalker(const WalkGraph& graph)
    : graph_(&graph), alone_(graph), stamp_(graph.positions.size(), 0) {}

void ClusterDiscWalker::walk(const DiscClusters& clusters, int k, double radius,
                             ClusterDiscs& out) {
    const WalkGraph& g = *graph_;
    const Eigen::Vector3d* p = g.positions.data();
    const int* offsets = g.neighbour_offsets.data();
    const int* neighbours = g.neighbours.data();
    const int* member = clusters.members.data() + clusters.offsets[k];
    const int n = clusters.size(k);
    const int c = member[0];
    const double rho = clusters.reach[k] * (1 + kMargin);
    out.core.clear();
    out.ring.clear();
    out.own.clear();
    out.own_offsets.assign(n + 1, 0);
    out.words = 0;
    out.masks.clear();

    if (!(2 * rho <= radius)) {  // too wide a cluster for the core to be shared: walk each alone
        for (int i = 0; i < n; ++i) {
            const IndexRange d = alone_.disc(member[i], radius);
            out.own.insert(out.own.end(), d.begin(), d.end());
            out.own_offsets[i + 1] = static_cast<int>(out.own.size());
        }
        return;
    }

    // Stamps: 2g in the core, 2g + 1 seen in this walk and not in the core.
    if (++generation_ >= (1u << 31)) {
        std::fill(stamp_.begin(), stamp_.end(), 0u);
        generation_ = 1;
    }
    const std::uint32_t in_core = 2 * generation_, seen = in_core + 1;
    std::uint32_t* stamp = stamp_.data();
    const double cx = p[c].x(), cy = p[c].y(), cz = p[c].z();
    const double r_in = (radius - rho) * (1 - kMargin), r_out = (radius + rho) * (1 + kMargin);
    const double in2 = r_in * r_in, out2 = r_out * r_out;
    auto fresh = [&](int u) { return (stamp[u] >> 1) != generation_; };

    // The core, breadth first from c; vertices between r_in and r_out start the ring.
    std::vector<int>& core = out.core;
    std::vector<int>& ring = out.ring;
    core.push_back(c);
    stamp[c] = in_core;
    parent_.clear();  // of each ring vertex: the vertex the walk reached it from
    for (std::size_t head = 0; head < core.size(); ++head) {
        const int v = core[head];
        for (int e = offsets[v]; e < offsets[v + 1]; ++e) {
            const int u = neighbours[e];
            if (!fresh(u)) continue;
            const double d2 = squared_distance(p[u], cx, cy, cz);
            if (d2 <= in2) {
                stamp[u] = in_core;
                core.push_back(u);
            } else {
                stamp[u] = seen;
                if (d2 <= out2) {
                    ring.push_back(u);
                    parent_.push_back(v);
                }
            }
        }
    }
    // The rest of N_{r_out}(c), reached through the ring.
    for (std::size_t head = 0; head < ring.size(); ++head) {
        const int v = ring[head];
        for (int e = offsets[v]; e < offsets[v + 1]; ++e) {
            const int u = neighbours[e];
            if (!fresh(u)) continue;
            stamp[u] = seen;
            if (squared_distance(p[u], cx, cy, cz) <= out2) {
                ring.push_back(u);
                parent_.push_back(v);
            }
        }
    }

    // Ring vertices with a neighbour closer to every point within rho of c; the others are
    // checked member by member. The ring's coordinates are copied apart so that the members'
    // distance tests run over three contiguous arrays.
    const int nr = static_cast<int>(ring.size());
    unproven_.clear();
    const double slack = kMargin * out2, four_rho2 = 4 * rho * rho;
    for (int j = 0; j < nr; ++j) {
        const int u = ring[j];
        const double du = squared_distance(p[u], cx, cy, cz);
        auto closer = [&](int w) {  // |w - c|^2 - |u - c|^2 + 2 rho |w - u| < -slack
            const double a = squared_distance(p[w], cx, cy, cz) - du + slack;
            return a < 0 && a * a > four_rho2 * (p[w] - p[u]).squaredNorm();
        };
        // The vertex the walk came from usually is such a neighbour; else try them all.
        bool good = closer(parent_[j]);
        for (int e = offsets[u]; e < offsets[u + 1] && !good; ++e) good = closer(neighbours[e]);
        if (!good) unproven_.push_back(j);
    }
    out.words = (nr + 63) / 64;
    const int padded = 64 * out.words;
    xs_.resize(padded);
    ys_.resize(padded);
    zs_.resize(padded);
    for (int j = 0; j < padded; ++j) {  // padding far away: never inside
        const Eigen::Vector3d& q = j < nr ? p[ring[j]] : Eigen::Vector3d(cx, cy, cz);
        xs_[j] = q.x();
        ys_[j] = q.y();
        zs_[j] = j < nr ? q.z() : std::numeric_limits<double>::infinity();
    }

    // Each member's part of the ring, and the members walked alone.
    out.masks.assign(static_cast<std::size_t>(n) * out.words, 0);
    const double r2 = radius * radius;
    for (int i = 0; i < n; ++i) {
        const int v = member[i];
        const double vx = p[v].x(), vy = p[v].y(), vz = p[v].z();
        std::uint64_t* mask = out.masks.data() + static_cast<std::size_t>(i) * out.words;
        for (int w = 0; w < out.words; ++w)
            mask[w] = inside_bits(xs_.data() + 64 * w, ys_.data() + 64 * w, zs_.data() + 64 * w, vx,
                                  vy, vz, r2);
        bool proven = stamp[v] == in_core;
        for (std::size_t t = 0; t < unproven_.size() && proven; ++t) {
            const int j = unproven_[t];
            if (!(mask[j >> 6] >> (j & 63) & 1)) continue;
            const int u = ring[j];
            const double d2 = squared_distance(p[u], vx, vy, vz);
            bool closer = false;
            for (int e = offsets[u]; e < offsets[u + 1] && !closer; ++e)
                closer = squared_distance(p[neighbours[e]], vx, vy, vz) < d2;
            proven = closer;
        }
        if (!proven) {
            std::fill(mask, mask + out.words, 0);
            const IndexRange d = alone_.disc(v, radius);
            out.own.insert(out.own.end(), d.begin(), d.end());
        }
        out.own_offsets[i + 1] = static_cast<int>(out.own.size());
    }
}

}  // namespace geotex
