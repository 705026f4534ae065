#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "common/errors.hpp"
#include "geometry/triangle_bvh.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

using Faces = std::vector<std::array<int, 3>>;
using Points = std::vector<Eigen::Vector3d>;

// The least squared distance from q to the faces of `group`, by a search over all of them.
double brute_d2(const Points& p, const Faces& faces, const std::vector<int>& group,
                const Eigen::Vector3d& q) {
    double best = std::numeric_limits<double>::infinity();
    for (int f : group)
        best = std::min(best, test::triangle_squared_distance(q, p[faces[f][0]], p[faces[f][1]],
                                                              p[faces[f][2]]));
    return best;
}

// `n` random triangles of side about 0.1 in the unit cube, each with its own corners.
void random_soup(int n, std::mt19937& rng, Points& p, Faces& faces) {
    std::uniform_real_distribution<double> u(0, 1), small(-0.05, 0.05);
    for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d c(u(rng), u(rng), u(rng));
        const int first = static_cast<int>(p.size());
        for (int k = 0; k < 3; ++k)
            p.push_back(c + Eigen::Vector3d(small(rng), small(rng), small(rng)));
        faces.push_back({first, first + 1, first + 2});
    }
}

}  // namespace

TEST_CASE("TriangleBvh: the least distance of each group equals a search over all its triangles",
          "[geometry][depth]") {
    std::mt19937 rng(7);
    Points p;
    Faces faces;
    random_soup(3000, rng, p, faces);
    // Three groups of interleaved faces: each query must see its own group's only.
    std::vector<std::vector<int>> groups(3);
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) groups[f % 3].push_back(f);
    std::vector<int> grouped, offsets{0};
    for (const auto& g : groups) {
        grouped.insert(grouped.end(), g.begin(), g.end());
        offsets.push_back(static_cast<int>(grouped.size()));
    }
    const TriangleBvh tree(p, faces, grouped, offsets);
    REQUIRE(tree.num_groups() == 3);
    std::uniform_real_distribution<double> u(-0.2, 1.2), wiggle(-0.03, 0.03);
    auto check_all = [&](const Points& at) {
        const TriangleBvh::Boxes boxes = tree.refit(at);
        for (int i = 0; i < 300; ++i) {
            const Eigen::Vector3d q(u(rng), u(rng), u(rng));
            const int g = i % 3;
            const double expected = brute_d2(at, faces, groups[g], q);
            const double got =
                tree.squared_distance(g, q, std::numeric_limits<double>::infinity(), boxes, at);
            REQUIRE(got == Approx(expected).epsilon(1e-12).margin(1e-15));
            // A bound below the answer is the answer: nothing is closer.
            CHECK(tree.squared_distance(g, q, expected / 2, boxes, at) == expected / 2);
        }
    };
    SECTION("at the positions it was built on") { check_all(p); }
    SECTION("refitted to moved corners, as a smoothed surface moves the mesh's vertices") {
        Points moved = p;
        for (auto& x : moved) x += Eigen::Vector3d(wiggle(rng), wiggle(rng), wiggle(rng));
        check_all(moved);
    }
}

TEST_CASE("TriangleBvh: the distance to a plane grid is the height above it", "[geometry][depth]") {
    const Mesh m = test::make_grid(40, 2.0);  // the plane z = 0
    std::vector<int> all(m.faces.size());
    for (int f = 0; f < m.num_faces(); ++f) all[f] = f;
    const TriangleBvh tree(m.positions, m.faces, all, {0, m.num_faces()});
    const TriangleBvh::Boxes boxes = tree.refit(m.positions);
    for (double h : {0.0, 1e-6, 0.25, 3.0}) {
        const Eigen::Vector3d q(0.3, -0.2, h);
        CHECK(tree.squared_distance(0, q, 1e9, boxes, m.positions) == Approx(h * h).margin(1e-24));
    }
    // Lifting the grid by 0.5 with the same tree: the distance follows the refitted surface.
    Points lifted = m.positions;
    for (auto& x : lifted) x.z() += 0.5;
    const TriangleBvh::Boxes lifted_boxes = tree.refit(lifted);
    CHECK(tree.squared_distance(0, Eigen::Vector3d(0.3, -0.2, 2.0), 1e9, lifted_boxes, lifted) ==
          Approx(2.25));
}

TEST_CASE("TriangleBvh: degenerate triangles are left out, and an empty group has no faces",
          "[geometry][depth]") {
    // Face 0 is a proper triangle in z = 0; face 1 has three collinear corners near the query.
    const Points p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 1}, {6, 5, 1}, {7, 5, 1}};
    const Faces faces = {{0, 1, 2}, {3, 4, 5}};
    const TriangleBvh tree(p, faces, {0, 1}, {0, 1, 2, 2});
    const TriangleBvh::Boxes boxes = tree.refit(p);
    CHECK(boxes.degenerate == std::vector<char>{0, 1});
    CHECK(tree.has_faces(0, boxes));
    CHECK_FALSE(tree.has_faces(1, boxes));  // only the degenerate face
    CHECK_FALSE(tree.has_faces(2, boxes));  // no face at all
    const Eigen::Vector3d q(6, 5, 1);       // on the degenerate face's middle corner
    CHECK(tree.squared_distance(1, q, 4.0, boxes, p) == 4.0);
    CHECK(tree.squared_distance(2, q, 4.0, boxes, p) == 4.0);
    CHECK(tree.squared_distance(0, Eigen::Vector3d(0.2, 0.2, 3), 1e9, boxes, p) == Approx(9.0));
}

TEST_CASE("TriangleBvh: bad groups, faces and sizes are refused", "[geometry][depth][errors]") {
    const Points p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const Faces faces = {{0, 1, 2}};
    CHECK_THROWS_AS(TriangleBvh(p, faces, {0}, {0, 2}), InvalidInput);  // offsets past the end
    CHECK_THROWS_AS(TriangleBvh(p, faces, {0}, {}), InvalidInput);
    CHECK_THROWS_AS(TriangleBvh(p, faces, {1}, {0, 1}), InvalidInput);  // no face 1
    const Faces bad = {{0, 1, 3}};
    CHECK_THROWS_AS(TriangleBvh(p, bad, {0}, {0, 1}), InvalidInput);  // no vertex 3
    const TriangleBvh tree(p, faces, {0}, {0, 1});
    CHECK_THROWS_AS(tree.refit({{0, 0, 0}}), InvalidInput);
    const TriangleBvh::Boxes boxes = tree.refit(p);
    CHECK_THROWS_AS(tree.squared_distance(1, Eigen::Vector3d::Zero(), 1, boxes, p), InvalidInput);
    CHECK_THROWS_AS(tree.squared_distance(0, Eigen::Vector3d::Zero(), 1, TriangleBvh::Boxes{}, p),
                    InvalidInput);
}
