#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "common/detail/numbers.hpp"
#include "geometry/disc_clusters.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

// A strip folded into a U: two sheets 2 x 0.03 apart joined by a half cylinder, so that a
// ball near the fold holds vertices of the other sheet that are joined to its centre only
// round the fold, or not at all inside the ball.
Mesh make_fold(int n) {
    Mesh m = test::make_grid(n, 1.0);
    const double straight = 0.45, bend = 0.03, length = 2 * straight + kPi * bend;
    for (auto& p : m.positions) {
        const double u = (p.x() + 0.5) * length;
        double x, z;
        if (u < straight) {
            x = u;
            z = 0;
        } else if (u < straight + kPi * bend) {
            const double a = (u - straight) / bend;
            x = straight + bend * std::sin(a);
            z = bend * (1 - std::cos(a));
        } else {
            x = straight - (u - straight - kPi * bend);
            z = 2 * bend;
        }
        p = Eigen::Vector3d(x, p.y(), z);
    }
    return m;
}

// A grid with its vertices moved in the plane and in height at random (skinny, non-Delaunay
// triangles), and a wall higher than the discs are wide.
Mesh make_rough(int n, unsigned seed) {
    Mesh m =
        test::make_grid(n, 1.0, [](double x, double) { return std::abs(x) < 0.02 ? 0.3 : 0.0; });
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.4 / n, 0.4 / n);
    for (auto& p : m.positions) p += Eigen::Vector3d(jitter(rng), jitter(rng), 0.5 * jitter(rng));
    return m;
}

std::vector<int> sorted(std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
}

struct Comparison {
    int mismatches = 0, own = 0, shared = 0;
};

// Every member's disc from its cluster's walk against its own breadth-first walk.
Comparison compare_with_walks(const Mesh& m, double r, double cluster_rel) {
    const MeshTopology t = make_topology(m);
    const WalkGraph g = make_walk_graph(m, t);
    const DiscClusters clusters = make_disc_clusters(g, cluster_rel * r);
    ClusterDiscWalker cw(g);
    DiscWalker w(g);
    ClusterDiscs cd;
    Comparison c;
    for (int k = 0; k < clusters.num_clusters(); ++k) {
        cw.walk(clusters, k, r, cd);
        for (int i = 0; i < clusters.size(k); ++i) {
            std::vector<int> disc;
            if (cd.has_own(i)) {
                ++c.own;
                disc.assign(cd.own_disc(i).begin(), cd.own_disc(i).end());
            } else {
                ++c.shared;
                disc = cd.core;
                for (int j = 0; j < static_cast<int>(cd.ring.size()); ++j)
                    if (cd.mask(i)[j >> 6] >> (j & 63) & 1) disc.push_back(cd.ring[j]);
            }
            const IndexRange walked = w.disc(clusters.members[clusters.offsets[k] + i], r);
            c.mismatches += sorted(disc) != sorted(std::vector<int>(walked.begin(), walked.end()));
        }
    }
    return c;
}

}  // namespace

TEST_CASE("make_disc_clusters: a cover of every vertex by clusters within the radius",
          "[geometry][neighbourhood]") {
    const Mesh m = test::combined(test::make_sphere(1.0, 4),
                                  test::make_sphere(0.5, 2, Eigen::Vector3d(3, 0, 0)));
    const MeshTopology t = make_topology(m);
    const WalkGraph g = make_walk_graph(m, t);
    const double radius = 0.2;
    const DiscClusters clusters = make_disc_clusters(g, radius);
    std::vector<int> seen(g.num_vertices(), 0);
    for (int u : clusters.members) ++seen[u];
    CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
    REQUIRE(clusters.num_clusters() > 1);
    REQUIRE(static_cast<int>(clusters.reach.size()) == clusters.num_clusters());
    double total = 0;
    for (int k = 0; k < clusters.num_clusters(); ++k) {
        const Eigen::Vector3d& c = g.positions[clusters.members[clusters.offsets[k]]];
        double reach = 0;
        for (int i = clusters.offsets[k]; i < clusters.offsets[k + 1]; ++i)
            reach = std::max(reach, (g.positions[clusters.members[i]] - c).norm());
        CHECK(reach == Approx(clusters.reach[k]).margin(1e-15));
        CHECK(clusters.reach[k] <= radius);
        total += clusters.size(k);
    }
    // Clusters of more than a vertex: on a level-4 sphere a ball of 0.2 holds about 25.
    CHECK(total / clusters.num_clusters() > 4);
    // A radius below the edges: one vertex per cluster.
    CHECK(make_disc_clusters(g, 1e-6).num_clusters() == g.num_vertices());
}

TEST_CASE("ClusterDiscWalker: the same discs as one walk per vertex", "[geometry][neighbourhood]") {
    SECTION("sphere") {
        const Comparison c = compare_with_walks(test::make_sphere(1.0, 4), 0.3, 0.25);
        CHECK(c.mismatches == 0);
        CHECK(c.own == 0);  // a convex surface: every ring vertex is proven from the cluster
    }
    SECTION("cylinder narrower than the discs") {
        const Comparison c = compare_with_walks(test::make_cylinder(0.2, 2.0, 24, 41), 0.5, 0.25);
        CHECK(c.mismatches == 0);
    }
    SECTION("two sheets joined by a fold") {
        for (double r : {0.05, 0.12, 0.2}) {
            INFO("radius " << r);
            const Comparison c = compare_with_walks(make_fold(60), r, 0.25);
            CHECK(c.mismatches == 0);
            CHECK(c.shared > 0);
            if (r > 0.06) CHECK(c.own > 0);  // the other sheet's nearest vertices: walked alone
        }
    }
    SECTION("jittered grid with a wall") {
        for (unsigned seed : {1u, 2u, 3u}) {
            INFO("seed " << seed);
            CHECK(compare_with_walks(make_rough(50, seed), 0.15, 0.25).mismatches == 0);
        }
    }
    SECTION("wider and narrower clusters, radius below the edges") {
        const Mesh m = make_fold(40);
        for (double rel : {0.0, 0.1, 0.5, 0.7}) {  // 0.7: too wide to share, every member alone
            INFO("cluster reach / r " << rel);
            CHECK(compare_with_walks(m, 0.12, rel).mismatches == 0);
        }
        CHECK(compare_with_walks(m, 1e-4, 0.25).mismatches == 0);
    }
}
