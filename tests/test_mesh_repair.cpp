#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"
#include "common/release.hpp"
#include "geometry/detail/repair_steps.hpp"
#include "geometry/icosphere.hpp"
#include "geometry/mesh_repair.hpp"
#include "tests/fixtures.hpp"
#include "tests/repair_soups.hpp"

using namespace geotex;
using namespace geotex::test;

namespace {

// Consistent orientation: no directed edge is used twice.
bool consistently_oriented(const Mesh& m) {
    std::set<std::pair<int, int>> directed;
    for (const auto& f : m.faces) {
        for (int k = 0; k < 3; ++k) {
            if (!directed.insert({f[k], f[(k + 1) % 3]}).second) return false;
        }
    }
    return true;
}

bool has_diagnostic(const MeshRepairResult& r, const std::string& message) {
    return std::any_of(r.diagnostics.begin(), r.diagnostics.end(), [&](const Diagnostic& d) {
        return d.stage == "mesh repair" && d.message == message;
    });
}

// The cube as 12 outward triangles, each quad split along its first diagonal.
Mesh cube_mesh(double k = 1.0) {
    Mesh m;
    m.positions = cube_positions(k);
    for (const auto& q : kCubeQuads) {
        m.faces.push_back({q[0], q[1], q[2]});
        m.faces.push_back({q[0], q[2], q[3]});
    }
    return m;
}

// A strip of 2 x `cells` triangles in the xy plane, all facing +z.
Mesh strip(int cells) {
    Mesh m;
    for (int i = 0; i <= cells; ++i) m.positions.emplace_back(i, 0, 0);
    for (int i = 0; i <= cells; ++i) m.positions.emplace_back(i, 1, 0);
    const int top = cells + 1;
    for (int i = 0; i < cells; ++i) {
        m.faces.push_back({i, i + 1, top + i + 1});
        m.faces.push_back({i, top + i + 1, top + i});
    }
    return m;
}

}  // namespace

TEST_CASE("repair_soup: a quad cube is triangulated and stays outward", "[geometry][mesh_repair]") {
    const MeshRepairResult r = repair_soup(make_soup(cube_positions(), kCubeQuads));
    // Both diagonals of a square are equally long: the split is along the first one.
    CHECK(r.mesh.faces == cube_mesh().faces);
    CHECK(r.mesh.positions == cube_positions());
    CHECK(r.source_polygon == std::vector<int>{0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5});
    CHECK(r.report.num_input_polygons == 6);
    CHECK(r.report.num_polygons_triangulated == 6);
    CHECK(r.report.num_faces_flipped == 0);
    CHECK(r.report.num_boundary_edges == 0);
    CHECK(r.report.num_components == 1);
    CHECK(r.report.num_closed_components == 1);
    // Volume of a unit cube from exact coordinates: only rounding of small sums, 1e-12.
    CHECK(signed_volume(r.mesh) == Approx(1.0).epsilon(1e-12));
    CHECK(has_diagnostic(r, "triangulated 6 polygons with more than 3 vertices"));
    CHECK(r.diagnostics.size() == 1);
}

TEST_CASE("repair_soup: a quad is split along its shorter diagonal", "[geometry][mesh_repair]") {
    const std::vector<Eigen::Vector3d> p = {{-2, 0, 0}, {0, -1, 0}, {2, 0, 0}, {0, 1, 0}};
    // Diagonal 0-2 is 4 long, 1-3 is 2 long.
    const MeshRepairResult r = repair_soup(make_soup(p, {{0, 1, 2, 3}}));
    CHECK(r.mesh.faces == std::vector<std::array<int, 3>>{{0, 1, 3}, {1, 2, 3}});
    const MeshRepairResult s = repair_soup(make_soup(p, {{1, 2, 3, 0}}));
    CHECK(s.mesh.faces == std::vector<std::array<int, 3>>{{1, 2, 3}, {1, 3, 0}});
    CHECK(s.report.num_boundary_edges == 4);
}

TEST_CASE("repair_soup: polygons with 5 or more vertices keep area and orientation",
          "[geometry][mesh_repair]") {
    // A convex hexagon and a non-convex L shape, counter-clockwise seen from +z.
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < 6; ++i) {
        const double a = 2.0 * kPi * i / 6.0;
        p.emplace_back(std::cos(a), std::sin(a), 0.0);
    }
    const double hexagon_area = 1.5 * std::sqrt(3.0);
    const std::vector<Eigen::Vector3d> l_shape = {{0, 0, 5}, {2, 0, 5}, {2, 1, 5},
                                                  {1, 1, 5}, {1, 2, 5}, {0, 2, 5}};
    p.insert(p.end(), l_shape.begin(), l_shape.end());
    const MeshRepairResult r =
        repair_soup(make_soup(p, {{0, 1, 2, 3, 4, 5}, {6, 7, 8, 9, 10, 11}}));
    REQUIRE(r.mesh.num_faces() == 8);
    CHECK(r.source_polygon == std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1});
    CHECK(r.report.num_polygons_triangulated == 2);
    double area[2] = {0.0, 0.0};
    for (int f = 0; f < r.mesh.num_faces(); ++f) {
        const auto& t = r.mesh.faces[f];
        const Eigen::Vector3d n = (r.mesh.positions[t[1]] - r.mesh.positions[t[0]])
                                      .cross(r.mesh.positions[t[2]] - r.mesh.positions[t[0]]);
        CHECK(n.z() > 0.0);  // same way round as the polygon
        area[r.source_polygon[f]] += 0.5 * n.norm();
    }
    // Sums of a few products of numbers near 1: rounding stays far below 1e-12.
    CHECK(area[0] == Approx(hexagon_area).epsilon(1e-12));
    CHECK(area[1] == Approx(3.0).epsilon(1e-12));
    CHECK(r.report.num_boundary_edges == 12);
    CHECK(consistently_oriented(r.mesh));
}

TEST_CASE("repair_soup: duplicate vertices of a triangle soup are merged",
          "[geometry][mesh_repair]") {
    const Mesh cube = cube_mesh();
    const PolygonSoup soup = own_corners_soup(cube);
    const MeshRepairResult r = repair_soup(soup);
    CHECK(r.report.num_input_vertices == 36);
    CHECK(r.report.num_duplicate_vertices_merged == 28);
    REQUIRE(r.mesh.num_vertices() == 8);
    // First-occurrence order: the corners as the faces first use them.
    std::vector<int> order;
    for (const auto& f : cube.faces) {
        for (int v : f) {
            if (std::find(order.begin(), order.end(), v) == order.end()) order.push_back(v);
        }
    }
    for (int i = 0; i < 8; ++i) CHECK(r.mesh.positions[i] == cube.positions[order[i]]);
    for (int f = 0; f < 12; ++f) {
        for (int k = 0; k < 3; ++k) {
            CHECK(order[r.mesh.faces[f][k]] == cube.faces[f][k]);
        }
    }
    CHECK(r.report.num_closed_components == 1);
    CHECK(r.report.num_isolated_vertices == 0);
    CHECK(has_diagnostic(r, "merged 28 duplicate vertices"));

    MeshRepairParams keep;
    keep.merge_duplicate_vertices = false;
    const MeshRepairResult k = repair_soup(soup, keep);
    CHECK(k.mesh.num_vertices() == 36);
    CHECK(k.report.num_duplicate_vertices_merged == 0);
    CHECK(k.report.num_boundary_edges == 36);
    CHECK(k.report.num_components == 12);
}

TEST_CASE("repair_soup: degenerate and duplicate faces are removed and counted",
          "[geometry][mesh_repair]") {
    const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
    const Polygons polygons = {
        {0, 1, 2},  // kept
        {0, 1, 1},  // repeated vertex
        {0, 2, 3},  // kept
        {0, 1, 4},  // three points on the x axis: zero area
        {2, 0, 1},  // same as the first, rotated
        {0, 2, 1},  // same as the first, reversed
        {3, 2, 0},  // same as the third, reversed
    };
    const MeshRepairResult r = repair_soup(make_soup(p, polygons));
    CHECK(r.mesh.faces == std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}});
    CHECK(r.source_polygon == std::vector<int>{0, 2});
    CHECK(r.report.num_degenerate_faces_removed == 2);
    CHECK(r.report.num_duplicate_faces_removed == 3);
    CHECK(r.report.num_isolated_vertices == 1);  // vertex 4, kept so indices stay put
    CHECK(r.mesh.num_vertices() == 5);
    CHECK(r.report.num_boundary_edges == 4);
    CHECK(has_diagnostic(r, "removed 2 degenerate faces (repeated vertex or zero area)"));
    CHECK(has_diagnostic(r, "removed 3 duplicate faces"));
    CHECK(has_diagnostic(r, "kept 1 isolated vertex that no face uses"));
}

TEST_CASE("repair_soup: nearly collinear faces are kept", "[geometry][mesh_repair]") {
    // The third corner is one ulp off the line: the exact test sees a (tiny) triangle.
    const std::vector<Eigen::Vector3d> p = {
        {0, 0, 0}, {1, 0, 0}, {2, std::numeric_limits<double>::denorm_min(), 0}};
    const MeshRepairResult r = repair_soup(make_soup(p, {{0, 1, 2}}));
    CHECK(r.mesh.num_faces() == 1);
    CHECK(r.report.num_degenerate_faces_removed == 0);
}

TEST_CASE("repair_soup: a cube with flipped faces comes out outward", "[geometry][mesh_repair]") {
    const Mesh cube = cube_mesh();
    for (double k : {1e-6, 1.0, 1e6}) {  // the answer does not depend on the scale
        Mesh input = cube_mesh(k);
        for (int f : {0, 5, 7}) input.faces[f] = flipped(input.faces[f]);
        const MeshRepairResult r = repair_soup(make_soup(input));
        CHECK(r.mesh.faces == cube.faces);
        CHECK(r.report.num_faces_flipped == 3);
        // Exact corners; the volume sum rounds only in the last bits.
        CHECK(signed_volume(r.mesh) == Approx(k * k * k).epsilon(1e-12));
        CHECK(has_diagnostic(r, "flipped 3 faces to orient them consistently"));

        Mesh inside_out = cube_mesh(k);
        for (auto& f : inside_out.faces) f = flipped(f);
        const MeshRepairResult s = repair_soup(make_soup(inside_out));
        CHECK(s.mesh.faces == cube.faces);
        CHECK(s.report.num_faces_flipped == 12);
        CHECK(signed_volume(s.mesh) > 0.0);
    }
}

TEST_CASE("repair_soup: an open strip with one flipped face is made consistent",
          "[geometry][mesh_repair]") {
    const Mesh s = strip(3);
    Mesh input = s;
    input.faces[2] = flipped(input.faces[2]);
    const MeshRepairResult r = repair_soup(make_soup(input));
    CHECK(r.mesh.faces == s.faces);
    CHECK(r.report.num_faces_flipped == 1);
    CHECK(r.report.num_boundary_edges == 8);
    CHECK(r.report.num_components == 1);
    CHECK(r.report.num_closed_components == 0);

    // Four of six flipped: the majority wins, so the other two are flipped.
    Mesh most = s;
    for (int f : {0, 1, 3, 5}) most.faces[f] = flipped(most.faces[f]);
    const MeshRepairResult m = repair_soup(make_soup(most));
    CHECK(m.report.num_faces_flipped == 2);
    CHECK(consistently_oriented(m.mesh));
    for (int f = 0; f < 6; ++f) CHECK(m.mesh.faces[f] == flipped(s.faces[f]));
}

TEST_CASE("repair_soup: two components are oriented and counted separately",
          "[geometry][mesh_repair]") {
    Mesh both = cube_mesh();
    const Mesh second = cube_mesh();
    for (const auto& p : second.positions) both.positions.push_back(p + Eigen::Vector3d(3, 0, 0));
    for (const auto& f : second.faces)
        both.faces.push_back(flipped({f[0] + 8, f[1] + 8, f[2] + 8}));
    Mesh open = strip(2);
    for (auto& p : open.positions) p += Eigen::Vector3d(0, 0, 5);
    const int base = both.num_vertices();
    for (const auto& p : open.positions) both.positions.push_back(p);
    for (const auto& f : open.faces) both.faces.push_back({f[0] + base, f[1] + base, f[2] + base});

    const MeshRepairResult r = repair_soup(make_soup(both));
    CHECK(r.report.num_components == 3);
    CHECK(r.report.num_closed_components == 2);
    CHECK(r.report.num_faces_flipped == 12);  // the second cube only
    CHECK(r.report.num_boundary_edges == 6);
    // Each cube encloses volume 1 outward (faces 0..23 are the cubes').
    Mesh cubes = r.mesh;
    cubes.faces.resize(24);
    CHECK(signed_volume(cubes) == Approx(2.0).epsilon(1e-12));
}

TEST_CASE("repair_soup: a non-manifold edge is counted and does not stop the repair",
          "[geometry][mesh_repair]") {
    // Three triangles on edge 0-1, like pages of a book.
    const std::vector<Eigen::Vector3d> p = {
        {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, -1, 0}};
    const MeshRepairResult r = repair_soup(make_soup(p, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
    CHECK(r.mesh.num_faces() == 3);
    CHECK(r.report.num_non_manifold_edges == 1);
    CHECK(r.report.num_boundary_edges == 6);
    CHECK(r.report.num_components == 1);  // joined through the non-manifold edge
    CHECK(r.report.num_closed_components == 0);
    CHECK(r.report.num_faces_flipped == 0);  // nothing propagates across that edge
    CHECK(has_diagnostic(r,
                         "found 1 non-manifold edge (more than two faces); orientation is "
                         "not propagated across them"));

    // A closed cube with an extra fin on one edge: the cube is no longer closed.
    Mesh fin = cube_mesh();
    fin.positions.emplace_back(0.5, -1.0, -1.0);
    fin.faces.push_back({0, 1, 8});
    const MeshRepairResult f = repair_soup(make_soup(fin));
    CHECK(f.report.num_non_manifold_edges == 1);
    CHECK(f.report.num_components == 1);
    CHECK(f.report.num_closed_components == 0);
}

TEST_CASE("repair_soup: a Moebius strip is reported as non-orientable", "[geometry][mesh_repair]") {
    const int n = 8;
    const MeshRepairResult r = repair_soup(moebius_strip(n));
    CHECK(r.mesh.num_faces() == 2 * n);
    CHECK(r.report.num_components == 1);
    CHECK(r.report.num_closed_components == 0);
    CHECK(r.report.num_boundary_edges == 2 * n);  // one boundary loop around twice
    CHECK(r.report.num_non_manifold_edges == 0);
    CHECK(std::any_of(r.diagnostics.begin(), r.diagnostics.end(), [](const Diagnostic& d) {
        return d.message.find("non-orientable") != std::string::npos;
    }));
}

TEST_CASE("repair_soup: a clean mesh comes out unchanged", "[geometry][mesh_repair]") {
    const Mesh sphere = make_icosphere(3);
    const MeshRepairResult r = repair_soup(make_soup(sphere));
    CHECK(r.mesh.positions == sphere.positions);
    CHECK(r.mesh.faces == sphere.faces);
    std::vector<int> identity(sphere.faces.size());
    for (std::size_t i = 0; i < identity.size(); ++i) identity[i] = static_cast<int>(i);
    CHECK(r.source_polygon == identity);
    CHECK(r.diagnostics.empty());
    CHECK(r.report.num_components == 1);
    CHECK(r.report.num_closed_components == 1);
    CHECK(r.report.num_boundary_edges == 0);
    CHECK(r.report.num_non_manifold_edges == 0);
    CHECK(r.report.num_isolated_vertices == 0);
}

TEST_CASE("repair_soup: orientation can be left alone", "[geometry][mesh_repair]") {
    Mesh input = cube_mesh();
    input.faces[4] = flipped(input.faces[4]);
    MeshRepairParams params;
    params.orient = false;
    const MeshRepairResult r = repair_soup(make_soup(input), params);
    CHECK(r.mesh.faces == input.faces);
    CHECK(r.report.num_faces_flipped == 0);
    CHECK(r.report.num_closed_components == 1);
}

TEST_CASE("repair_soup: invalid soups throw InvalidInput", "[geometry][mesh_repair]") {
    const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    auto message = [](const PolygonSoup& s) {
        try {
            repair_soup(s);
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("no exception");
    };
    CHECK(message(make_soup(p, {{0, 1, 2}, {0, 1, 3}, {0, 1, 7}})) ==
          "repair_soup: 2 polygons reference a vertex out of range (first: polygon 1 uses index "
          "3, but the soup has 3 vertices)");
    CHECK(message(make_soup(p, {{0, -1, 2}})).find("uses index -1") != std::string::npos);
    CHECK(message(make_soup(p, {{0, 1, 2}, {0, 1}})) ==
          "repair_soup: 1 polygon has fewer than 3 vertices (first: polygon 1 with 2)");
    std::vector<Eigen::Vector3d> nan = p;
    nan[2].y() = std::numeric_limits<double>::quiet_NaN();
    CHECK(message(make_soup(nan, {{0, 1, 2}})).find("first: vertex 2") != std::string::npos);
    CHECK(message(make_soup(p, {})) == "repair_soup: the soup has no polygons");
    CHECK(message(make_soup(p, {{0, 1, 1}, {0, 0, 0}})).find("no non-degenerate face") !=
          std::string::npos);
    PolygonSoup broken = make_soup(p, {{0, 1, 2}});
    broken.face_offsets.back() = 5;
    REQUIRE_THROWS_AS(repair_soup(broken), InvalidInput);
    PolygonSoup jumping = make_soup(p, {{0, 1, 2}, {0, 1, 2}});
    jumping.face_offsets = {0, 10, 6};  // past the end, then back
    REQUIRE_THROWS_AS(repair_soup(jumping), InvalidInput);
}

TEST_CASE("repair_soup: a soup given up gives the same mesh as one kept, and is left empty",
          "[geometry][mesh_repair]") {
    const PolygonSoup kept = every_step_soup();
    const MeshRepairResult a = repair_soup(kept);
    PolygonSoup given = kept;
    const MeshRepairResult b = repair_soup(std::move(given));

    // What the soup needed was done.
    CHECK(a.report.num_duplicate_vertices_merged > 0);
    CHECK(a.report.num_polygons_triangulated == 7);
    CHECK(a.report.num_degenerate_faces_removed == 1);
    CHECK(a.report.num_duplicate_faces_removed == 1);
    CHECK(a.report.num_faces_flipped > 0);
    CHECK(a.report.num_non_manifold_edges == 1);
    // And the same, every value.
    require_same_repair(a, b);
    // The kept soup is untouched; the given one holds nothing.
    CHECK(kept.positions == every_step_soup().positions);
    CHECK(given.positions.empty());
    CHECK(given.face_indices.empty());
    CHECK(given.num_polygons() == 0);
}

// ---- the repair in tiles (MeshRepairParams::tiles) -----------------------------------------

TEST_CASE("repair_soup without the sources gives the same mesh and report, and no sources",
          "[geometry][mesh_repair]") {
    // Every step drops or adds faces: the triangulation, the degenerate and duplicate faces.
    for (const PolygonSoup& soup : {every_step_soup(), own_corners_soup(mixed_scene())}) {
        MeshRepairResult a = repair_soup(soup);
        REQUIRE(a.source_polygon.size() == a.mesh.faces.size());
        a.source_polygon.clear();
        for (int tiles : {1, 4}) {
            MeshRepairParams params;
            params.tiles = tiles;
            params.keep_sources = false;
            require_same_repair(a, repair_soup(soup, params));
        }
    }
}

TEST_CASE("release gives a vector's memory back", "[geometry][mesh_repair]") {
    // The repair releases its large arrays (the new vertex numbers, the edges) before its next
    // step; an array emptied but still allocated would stay in the step's peak.
    std::vector<int> remap(1000, 7);
    release(remap);
    CHECK(remap.empty());
    CHECK(remap.capacity() == 0);
    std::vector<std::pair<int, int>> pairs(10, {1, 2});
    release(pairs);
    CHECK(pairs.capacity() == 0);
}

TEST_CASE("merging vertices finds the same first occurrences in any number of passes",
          "[geometry][mesh_repair]") {
    // 3,000 vertices on 500 distinct positions, each repeated at scattered places; two differ
    // only in the sign of a zero, which is another bit pattern and so not merged.
    std::vector<Eigen::Vector3d> positions;
    for (int v = 0; v < 3000; ++v) {
        const int p = (v * 7919) % 500;
        positions.emplace_back(p, 0.25 * p, p % 3 == 0 ? 0.0 : 1.0 / p);
    }
    positions[2999] = {0.0, 0.0, -0.0};  // vertex 0's position but for the sign of a zero
    // The answer by brute force: the first vertex with the same coordinate bits.
    const auto same_position = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
        return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z());
    };
    std::vector<int> expected(positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v) {
        std::size_t u = 0;
        while (!same_position(positions[u], positions[v])) ++u;
        expected[v] = static_cast<int>(u);
    }
    REQUIRE(expected[2999] == 2999);
    for (int passes : {1, 2, 3, 7, 64})
        CHECK(detail::first_occurrences(positions, passes) == expected);
    // Numbered in order of first occurrence, each merged vertex kept once.
    std::vector<int> remap = expected;
    std::vector<int> kept;
    detail::number_first_occurrences(remap, [&](int v) { kept.push_back(v); });
    REQUIRE(kept.size() == 501);
    CHECK(std::is_sorted(kept.begin(), kept.end()));
    for (std::size_t v = 0; v < positions.size(); ++v)
        CHECK(same_position(positions[kept[static_cast<std::size_t>(remap[v])]], positions[v]));
}

TEST_CASE("merging vertices tells apart positions whose hashes share their 32 bits of key",
          "[geometry][mesh_repair]") {
    // 400,000 vertices, a fifth of them repeats of earlier ones: among some 320,000 distinct
    // positions, pairs whose keys collide are expected (about 12 in one pass, n^2 / 2^33),
    // and each must stay apart while the repeats join their first occurrence.
    std::mt19937_64 random(2026);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    std::vector<Eigen::Vector3d> positions;
    std::vector<int> expected;
    for (int v = 0; v < 400000; ++v) {
        if (v % 5 == 4) {
            const int earlier = static_cast<int>(random() % static_cast<std::uint64_t>(v));
            positions.push_back(positions[earlier]);
            expected.push_back(expected[earlier]);
        } else {
            positions.emplace_back(coordinate(random), coordinate(random), coordinate(random));
            expected.push_back(v);
        }
    }
    for (int passes : {1, 3}) CHECK(detail::first_occurrences(positions, passes) == expected);
}
