#include "tests/repair_soups.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "common/detail/numbers.hpp"
#include "geometry/icosphere.hpp"
#include "tests/fixtures.hpp"

namespace geotex::test {

std::array<int, 3> flipped(const std::array<int, 3>& f) { return {f[0], f[2], f[1]}; }

PolygonSoup make_soup(const std::vector<Eigen::Vector3d>& positions, const Polygons& polygons) {
    PolygonSoup s;
    s.positions = positions;
    for (const auto& p : polygons) {
        s.face_indices.insert(s.face_indices.end(), p.begin(), p.end());
        s.face_offsets.push_back(static_cast<int>(s.face_indices.size()));
    }
    return s;
}

PolygonSoup make_soup(const Mesh& m) {
    Polygons polygons;
    for (const auto& f : m.faces) polygons.push_back({f[0], f[1], f[2]});
    return make_soup(m.positions, polygons);
}

PolygonSoup own_corners_soup(const Mesh& m) {
    std::vector<Eigen::Vector3d> positions;
    Polygons polygons;
    for (const auto& f : m.faces) {
        const int base = static_cast<int>(positions.size());
        for (int v : f) positions.push_back(m.positions[v]);
        polygons.push_back({base, base + 1, base + 2});
    }
    return make_soup(positions, polygons);
}

std::vector<Eigen::Vector3d> cube_positions(double k) {
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < 8; ++i) p.emplace_back(k * (i & 1), k * ((i >> 1) & 1), k * (i >> 2));
    return p;
}

extern const Polygons kCubeQuads;
const Polygons kCubeQuads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

PolygonSoup moebius_strip(int n) {
    std::vector<Eigen::Vector3d> positions;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * kPi * i / n;
        const Eigen::Vector3d radial(std::cos(a), std::sin(a), 0);
        const Eigen::Vector3d across =
            std::cos(a / 2) * radial + std::sin(a / 2) * Eigen::Vector3d::UnitZ();
        positions.push_back(3 * radial - 0.5 * across);  // 2i: one edge of the band
        positions.push_back(3 * radial + 0.5 * across);  // 2i+1: the other
    }
    Polygons quads;
    for (int i = 0; i < n; ++i) {
        const int b0 = 2 * i, t0 = 2 * i + 1;
        // After a full turn the band has turned half over: the sides swap.
        const int b1 = i + 1 < n ? 2 * (i + 1) : 1;
        const int t1 = i + 1 < n ? 2 * (i + 1) + 1 : 0;
        quads.push_back({b0, b1, t1, t0});
    }
    return make_soup(positions, quads);
}

PolygonSoup every_step_soup() {
    const Mesh sphere = make_icosphere(2);
    std::vector<Eigen::Vector3d> positions;
    Polygons polygons;
    for (std::size_t f = 0; f < sphere.faces.size(); ++f) {
        const std::array<int, 3> t = f % 5 == 0 ? flipped(sphere.faces[f]) : sphere.faces[f];
        const int base = static_cast<int>(positions.size());
        for (int v : t) positions.push_back(sphere.positions[v] * 3.0);
        polygons.push_back({base, base + 1, base + 2});
    }
    const int cube = static_cast<int>(positions.size());
    for (const Eigen::Vector3d& p : cube_positions()) positions.push_back(p);
    for (const auto& q : kCubeQuads)
        polygons.push_back({cube + q[0], cube + q[1], cube + q[2], cube + q[3]});
    const int ring = static_cast<int>(positions.size());
    for (int i = 0; i < 5; ++i)
        positions.emplace_back(5 + std::cos(1.2566 * i), std::sin(1.2566 * i), 0);
    polygons.push_back({ring, ring + 1, ring + 2, ring + 3, ring + 4});
    polygons.push_back({ring, ring + 1, ring + 1});  // degenerate
    polygons.push_back(polygons.front());            // duplicate
    positions.emplace_back(0.5, -1, 0);
    polygons.push_back({cube + 0, cube + 1, static_cast<int>(positions.size()) - 1});

    return make_soup(positions, polygons);
}

Mesh randomly_flipped(Mesh mesh, double p, unsigned seed) {
    std::mt19937 rng(seed);
    std::bernoulli_distribution flip(p);
    for (auto& f : mesh.faces)
        if (flip(rng)) f = flipped(f);
    return mesh;
}

Mesh moved(Mesh mesh, const Eigen::Vector3d& by) {
    for (Eigen::Vector3d& p : mesh.positions) p += by;
    return mesh;
}

Mesh mixed_scene() {
    using test::combined;
    Mesh scene = randomly_flipped(test::make_sphere(1.0, 3), 0.3, 1);
    Mesh inside_out = test::make_sphere(0.4, 2, Eigen::Vector3d(2.2, 0.3, 0.1));
    for (auto& f : inside_out.faces) f = flipped(f);
    scene = combined(scene, inside_out);
    // Fins: a third face on some edges of the grid.
    Mesh grid = randomly_flipped(moved(test::make_grid(12, 3.0), {-1.5, -1.5, -1.6}), 0.7, 2);
    const int grid_faces = grid.num_faces();
    for (int f = 0; f < grid_faces; f += 11) {
        const auto& t = grid.faces[f];
        grid.positions.push_back(0.5 * (grid.positions[t[0]] + grid.positions[t[1]]) +
                                 Eigen::Vector3d(0.05, 0.07, 0.11));
        grid.faces.push_back({t[0], t[1], grid.num_vertices() - 1});
    }
    scene = combined(scene, grid);
    scene = combined(
        scene,
        randomly_flipped(moved(test::make_cylinder(0.3, 2.0, 16, 10), {-2.0, 0.5, -1.0}), 0.2, 3));
    const int nf = scene.num_faces();
    for (int f = 0; f < nf; f += 37)
        scene.faces.push_back(f % 2 ? flipped(scene.faces[f]) : scene.faces[f]);
    return scene;
}

void require_same_repair(const MeshRepairResult& a, const MeshRepairResult& b) {
    CHECK(b.mesh.positions == a.mesh.positions);
    CHECK(b.mesh.faces == a.mesh.faces);
    CHECK(b.source_polygon == a.source_polygon);
    const MeshRepairReport& x = a.report;
    const MeshRepairReport& y = b.report;
    CHECK(y.num_input_vertices == x.num_input_vertices);
    CHECK(y.num_input_polygons == x.num_input_polygons);
    CHECK(y.num_polygons_triangulated == x.num_polygons_triangulated);
    CHECK(y.num_duplicate_vertices_merged == x.num_duplicate_vertices_merged);
    CHECK(y.num_degenerate_faces_removed == x.num_degenerate_faces_removed);
    CHECK(y.num_duplicate_faces_removed == x.num_duplicate_faces_removed);
    CHECK(y.num_faces_flipped == x.num_faces_flipped);
    CHECK(y.num_isolated_vertices == x.num_isolated_vertices);
    CHECK(y.num_boundary_edges == x.num_boundary_edges);
    CHECK(y.num_non_manifold_edges == x.num_non_manifold_edges);
    CHECK(y.num_components == x.num_components);
    CHECK(y.num_closed_components == x.num_closed_components);
    REQUIRE(b.diagnostics.size() == a.diagnostics.size());
    for (std::size_t i = 0; i < a.diagnostics.size(); ++i)
        CHECK(b.diagnostics[i].message == a.diagnostics[i].message);
}

}  // namespace geotex::test
