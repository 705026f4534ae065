#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <utility>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"
#include "geometry/detail/repair_steps.hpp"
#include "geometry/mesh_repair.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;
using geotex::test::signed_volume;

namespace {

using Polygons = std::vector<std::vector<int>>;

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

// `m` as a soup in which every triangle has its own three corners (as STL stores them), for
// the repair to merge.
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

// Unit cube, vertex x + 2y + 4z at (x, y, z); quads counter-clockwise seen from outside.
std::vector<Eigen::Vector3d> cube_positions(double k = 1.0) {
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < 8; ++i) p.emplace_back(k * (i & 1), k * ((i >> 1) & 1), k * (i >> 2));
    return p;
}

const Polygons kCubeQuads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

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

// Icosphere: an icosahedron subdivided `level` times, outward faces.
Mesh icosphere(int level) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    Mesh m;
    const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                             {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                             {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (const auto& p : v) m.positions.push_back(Eigen::Vector3d(p[0], p[1], p[2]).normalized());
    m.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
               {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<int, int>, int> middle;
        auto mid = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            const auto it = middle.find(key);
            if (it != middle.end()) return it->second;
            m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
            return middle[key] = m.num_vertices() - 1;
        };
        std::vector<std::array<int, 3>> faces;
        for (const auto& f : m.faces) {
            const int a = mid(f[0], f[1]), b = mid(f[1], f[2]), c = mid(f[2], f[0]);
            faces.push_back({f[0], a, c});
            faces.push_back({f[1], b, a});
            faces.push_back({f[2], c, b});
            faces.push_back({a, b, c});
        }
        m.faces = faces;
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

std::array<int, 3> flipped(const std::array<int, 3>& f) { return {f[0], f[2], f[1]}; }

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

namespace {

// Two repairs of one soup gave the same mesh, sources, report and notes.
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

// A band of n quads around a circle of radius 3 that turns half over on the way.
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

// Every step of the repair at once: an icosphere as a triangle soup with its own corners
// (vertices to merge) and flipped faces, the cube as quads, a pentagon, a degenerate and a
// duplicate face, and a third face on one of the cube's edges (non-manifold).
PolygonSoup every_step_soup() {
    const Mesh sphere = icosphere(2);
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

}  // namespace

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
    const Mesh sphere = icosphere(3);
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

namespace {

std::vector<int> identity(std::size_t n) {
    std::vector<int> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<int>(i);
    return v;
}

// Steps (4) and (5) in `tiles` tiles against the whole mesh's, on a triangle mesh without
// degenerate faces: the tiles decide (no fall-back to the whole mesh) and give the same faces,
// sources, flips and counts.
void require_tiles_agree(const Mesh& mesh, int tiles, bool orient = true) {
    Mesh whole = mesh;
    std::vector<int> whole_source = identity(mesh.faces.size());
    const detail::OrientedFaces w = detail::orient_whole(whole, whole_source, orient);
    Mesh tiled = mesh;
    std::vector<int> tiled_source = identity(mesh.faces.size());
    const std::optional<detail::OrientedFaces> t =
        detail::orient_in_tiles(tiled, tiled_source, orient, tiles);
    REQUIRE(t.has_value());
    CHECK(tiled.faces == whole.faces);
    CHECK(tiled_source == whole_source);
    CHECK(t->flip == w.flip);
    CHECK(t->num_duplicates == w.num_duplicates);
    CHECK(t->num_boundary_edges == w.num_boundary_edges);
    CHECK(t->num_non_manifold_edges == w.num_non_manifold_edges);
    CHECK(t->num_components == w.num_components);
    CHECK(t->num_closed_components == w.num_closed_components);
    CHECK(t->num_conflicts == 0);
    CHECK(w.num_conflicts == 0);
}

// `mesh` with each face reversed with probability `p` (a fixed seed).
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

// Closed and open pieces of several sizes, some turned inside out or mostly reversed, with
// duplicate faces (some reversed) and faces on a third side of an edge, spread over the tiles.
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

}  // namespace

TEST_CASE("repair in tiles: a sphere with reversed faces is oriented as the whole mesh is",
          "[geometry][mesh_repair]") {
    const Mesh sphere = randomly_flipped(test::make_sphere(1.0, 4), 0.4, 7);
    for (int tiles : {2, 4, 9, 16}) {
        INFO(tiles << " tiles");
        require_tiles_agree(sphere, tiles);
    }
    // Outward: every reversed face flipped back, and only those.
    Mesh tiled = sphere;
    std::vector<int> source = identity(sphere.faces.size());
    const auto t = detail::orient_in_tiles(tiled, source, true, 9);
    REQUIRE(t);
    const Mesh reference = test::make_sphere(1.0, 4);
    for (std::size_t f = 0; f < tiled.faces.size(); ++f)
        CHECK((t->flip[f] != 0) == (sphere.faces[f] != reference.faces[f]));
    CHECK(t->num_closed_components == 1);
}

TEST_CASE("repair in tiles: pieces open and closed, duplicates and non-manifold edges",
          "[geometry][mesh_repair]") {
    const Mesh scene = mixed_scene();
    for (int tiles : {2, 4, 9, 16, 25}) {
        INFO(tiles << " tiles");
        require_tiles_agree(scene, tiles);
        require_tiles_agree(scene, tiles, false);
    }
    // The scene holds what the test means it to.
    Mesh whole = scene;
    std::vector<int> source = identity(scene.faces.size());
    const detail::OrientedFaces w = detail::orient_whole(whole, source, true);
    CHECK(w.num_duplicates > 50);
    CHECK(w.num_non_manifold_edges > 10);
    CHECK(w.num_closed_components == 2);  // the spheres
    CHECK(w.num_components == 4);
    CHECK(std::count(w.flip.begin(), w.flip.end(), 1) > 500);
}

TEST_CASE("repair in tiles: what the tiles cannot tell is left to the whole mesh",
          "[geometry][mesh_repair]") {
    SECTION("a Moebius strip cannot be oriented") {
        MeshRepairResult strip = repair_soup(moebius_strip(40));
        Mesh mesh = strip.mesh;
        std::vector<int> source = identity(mesh.faces.size());
        CHECK_FALSE(detail::orient_in_tiles(mesh, source, true, 4).has_value());
        CHECK(mesh.faces == strip.mesh.faces);  // untouched
        require_tiles_agree(strip.mesh, 4, false);
    }
    SECTION("a flat closed surface has no volume to orient it by") {
        // Four points of a plane, joined as a tetrahedron: closed, volume 0.
        Mesh flat;
        flat.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1.5, 0}};
        flat.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
        std::vector<int> source = identity(4);
        CHECK_FALSE(detail::orient_in_tiles(flat, source, true, 4).has_value());
    }
    SECTION("repair_soup then does it whole: the same result") {
        for (const PolygonSoup& soup : {moebius_strip(40), every_step_soup()}) {
            MeshRepairParams tiled;
            tiled.tiles = 4;
            require_same_repair(repair_soup(soup), repair_soup(soup, tiled));
        }
    }
}

TEST_CASE("repair in tiles: repair_soup gives the whole repair's mesh, sources and report",
          "[geometry][mesh_repair]") {
    // Every face with its own corners, so that vertices merge too.
    const PolygonSoup soup = own_corners_soup(mixed_scene());
    const MeshRepairResult a = repair_soup(soup);
    for (int tiles : {4, 9}) {
        MeshRepairParams params;
        params.tiles = tiles;
        require_same_repair(a, repair_soup(soup, params));
    }
}

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
