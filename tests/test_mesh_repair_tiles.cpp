// The repair's steps (4) and (5) a tile at a time (MeshRepairParams::tiles, docs/tiles.md)
// against the whole mesh's.
#include <algorithm>
#include <catch2/catch.hpp>
#include <optional>
#include <vector>

#include "geometry/detail/repair_steps.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/work_progress.hpp"
#include "tests/fixtures.hpp"
#include "tests/repair_soups.hpp"

using namespace geotex;
using namespace geotex::test;

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
    const detail::OrientedFaces w =
        detail::orient_whole(whole.positions, whole.faces, whole_source, orient);
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
    const detail::OrientedFaces w =
        detail::orient_whole(whole.positions, whole.faces, source, true);
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

TEST_CASE("repair in tiles: the tiles report how far they are, by the faces they own",
          "[geometry][mesh_repair][progress]") {
    const Mesh sphere = randomly_flipped(test::make_sphere(1.0, 4), 0.4, 7);
    const long long nf = static_cast<long long>(sphere.faces.size());
    std::vector<long long> done;  // the reports of the tiles' loop, by their total
    {
        // No delay, no interval and no least size: every tile reports.
        WorkProgressScope scope(
            [&](const WorkProgress& w) {
                if (w.total == nf) done.push_back(w.done);
            },
            0.0, 0.0, 1);
        Mesh tiled = sphere;
        std::vector<int> source = identity(sphere.faces.size());
        REQUIRE(detail::orient_in_tiles(tiled, source, true, 9));
    }
    REQUIRE(done.size() >= 9);
    CHECK(std::is_sorted(done.begin(), done.end()));
    CHECK(done.front() > 0);
    CHECK(done.back() == nf);  // every face is owned by one tile
}
