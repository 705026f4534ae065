#include <algorithm>
#include <catch2/catch.hpp>

#include "common/errors.hpp"
#include "geometry/neighbourhood.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {
std::vector<int> sorted(std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
}

std::vector<int> sorted_disc(DiscWalker& w, int v, double r) {
    const IndexRange range = w.disc(v, r);
    std::vector<int> d(range.begin(), range.end());
    std::sort(d.begin(), d.end());
    return d;
}
}  // namespace

TEST_CASE("DiscWalker: on a plane the disc is exactly the ball", "[geometry][neighbourhood]") {
    const Mesh m = test::make_grid(20, 1.0);
    const MeshTopology t = make_topology(m);
    DiscWalker w(m, t);
    const int center = 10 * 21 + 10;  // the grid centre
    for (double r : {0.04, 0.13, 0.3}) {
        std::vector<int> expected;
        for (int v = 0; v < m.num_vertices(); ++v)
            if ((m.positions[v] - m.positions[center]).norm() <= r) expected.push_back(v);
        CHECK(sorted_disc(w, center, r) == expected);
        CHECK(w.disc(center, r)[0] == center);
    }
    // A radius below the edge length holds the centre alone.
    CHECK(w.disc(center, 1e-3).size() == 1);
}

TEST_CASE("DiscWalker: does not cross a thin gap between two sheets", "[geometry][neighbourhood]") {
    // Two parallel planes 0.01 apart; the ball of radius 0.2 reaches the other sheet, the
    // geodesic disc must not.
    Mesh top = test::make_grid(10, 1.0, [](double, double) { return 0.01; });
    const Mesh both = test::combined(test::make_grid(10, 1.0), top);
    const MeshTopology t = make_topology(both);
    DiscWalker w(both, t);
    const int center = 5 * 11 + 5;
    const IndexRange d = w.disc(center, 0.2);
    CHECK(d.size() > 5);             // the disc reached several rings
    for (int v : d) CHECK(v < 121);  // all on the first sheet
    // A Euclidean ball query would have found vertices of the second sheet.
    int other_in_ball = 0;
    for (int v = 121; v < both.num_vertices(); ++v)
        other_in_ball += (both.positions[v] - both.positions[center]).norm() <= 0.2;
    CHECK(other_in_ball > 5);
}

TEST_CASE("DiscWalker: same disc after rescaling by 10^k", "[geometry][neighbourhood]") {
    const Mesh m = test::make_sphere(1.0, 3);
    const MeshTopology t = make_topology(m);
    DiscWalker w(m, t);
    const auto reference = sorted_disc(w, 7, 0.3);
    for (double k : {1e-3, 1e3}) {
        const Mesh s = test::scaled(m, k);
        DiscWalker ws(s, t);
        CHECK(sorted_disc(ws, 7, 0.3 * k) == reference);
    }
}

TEST_CASE("DiscWalker: walks stop at the sphere, not at a path length",
          "[geometry][neighbourhood]") {
    // On a cylinder of radius 1 the disc of radius 1.5 wraps around: all its vertices are
    // within 1.5 of the centre, and every vertex within 1.5 that is connected inside the ball
    // is found.
    const Mesh m = test::make_cylinder(1.0, 4.0, 24, 25);
    const MeshTopology t = make_topology(m);
    DiscWalker w(m, t);
    const int center = 12 * 24;
    const auto d = sorted_disc(w, center, 1.5);
    for (int v : d) CHECK((m.positions[v] - m.positions[center]).norm() <= 1.5);
    int in_ball = 0;
    for (int v = 0; v < m.num_vertices(); ++v)
        in_ball += (m.positions[v] - m.positions[center]).norm() <= 1.5;
    CHECK(static_cast<int>(d.size()) == in_ball);  // the cylinder part in the ball is connected
}

TEST_CASE("DiscWalker: find_in_disc stops at the first match in breadth-first order",
          "[geometry][neighbourhood]") {
    const Mesh m = test::make_sphere(1.0, 3);
    const MeshTopology t = make_topology(m);
    DiscWalker w(m, t);
    for (int center : {0, 7, 100}) {
        const IndexRange d = w.disc(center, 0.5);
        const std::vector<int> order(d.begin(), d.end());
        // The first vertex of the disc above the centre's height, if any.
        auto higher = [&](int u) { return m.positions[u].z() > m.positions[center].z() + 0.1; };
        int expected = -1;
        for (int u : order)
            if (higher(u)) {
                expected = u;
                break;
            }
        CHECK(w.find_in_disc(center, 0.5, higher) == expected);
        CHECK(w.find_in_disc(center, 0.5, [](int) { return false; }) == -1);
        CHECK(w.find_in_disc(center, 0.5, [&](int u) { return u == center; }) == center);
        // The walker is still usable for discs afterwards.
        const IndexRange again = w.disc(center, 0.5);
        CHECK(std::vector<int>(again.begin(), again.end()) == order);
    }
}

TEST_CASE("make_walk_graph: walks visit the mesh's discs in the same order",
          "[geometry][neighbourhood]") {
    const Mesh m = test::combined(test::make_sphere(1.0, 3),
                                  test::make_sphere(0.5, 2, Eigen::Vector3d(3, 0, 0)));
    const MeshTopology t = make_topology(m);
    DiscWalker on_mesh(m, t);
    const WalkGraph all = make_walk_graph(m, t);
    REQUIRE(all.num_vertices() == m.num_vertices());
    DiscWalker on_graph(all);
    for (int v = 0; v < m.num_vertices(); v += 37) {
        for (double r : {0.1, 0.45}) {
            const IndexRange expected = on_mesh.disc(v, r);
            std::vector<int> walked;
            for (int i : on_graph.disc(all.graph_vertex[v], r))
                walked.push_back(all.mesh_vertex[i]);
            CHECK(walked == std::vector<int>(expected.begin(), expected.end()));
        }
    }
    // The graph of one component holds its vertices only.
    std::vector<char> second(m.num_vertices(), 0);
    const int first_size = test::make_sphere(1.0, 3).num_vertices();
    for (int v = first_size; v < m.num_vertices(); ++v) second[v] = 1;
    const WalkGraph part = make_walk_graph(m, t, second);
    CHECK(part.num_vertices() == m.num_vertices() - first_size);
    CHECK(part.graph_vertex[0] == -1);
    for (int i = 0; i < part.num_vertices(); ++i) CHECK(part.mesh_vertex[i] >= first_size);
    // Half a component is refused: its walks would stop at the cut.
    std::vector<char> half(m.num_vertices(), 0);
    for (int v = 0; v < first_size / 2; ++v) half[v] = 1;
    REQUIRE_THROWS_AS(make_walk_graph(m, t, half), InvalidInput);
    REQUIRE_THROWS_AS(make_walk_graph(m, t, std::vector<char>(3, 1)), InvalidInput);
}

TEST_CASE("morton_order: the flagged points along a space-filling curve",
          "[geometry][neighbourhood]") {
    // A 16 x 16 grid of points numbered row by row: along the curve each 2 x 2 block of
    // neighbours comes out together, so consecutive points are far closer on average than
    // in row order (whose row ends jump across the grid).
    std::vector<Eigen::Vector3d> p;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) p.emplace_back(x, y, 0);
    const std::vector<int> order = morton_order(p);
    REQUIRE(order.size() == p.size());
    CHECK(sorted(order) == [&] {
        std::vector<int> all(p.size());
        for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
        return all;
    }());
    CHECK(std::vector<int>(order.begin(), order.begin() + 4) == std::vector<int>{0, 1, 16, 17});
    // Only the flagged points, in the same relative order.
    std::vector<char> even(p.size(), 0);
    for (std::size_t i = 0; i < p.size(); i += 2) even[i] = 1;
    std::vector<int> expected;
    for (int i : order)
        if (even[i]) expected.push_back(i);
    CHECK(morton_order(p, even) == expected);
    // Ties (equal points) by index; nothing flagged, nothing out; a wrong size refused.
    CHECK(morton_order(std::vector<Eigen::Vector3d>(5, Eigen::Vector3d(1, 2, 3))) ==
          std::vector<int>{0, 1, 2, 3, 4});
    CHECK(morton_order(p, std::vector<char>(p.size(), 0)).empty());
    REQUIRE_THROWS_AS(morton_order(p, std::vector<char>(3, 1)), InvalidInput);
}
