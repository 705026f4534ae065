// The repair with its faces on disk (repair_soup_on_disk, ScratchFile) against the repair that
// holds them.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/repair_steps.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/scratch_file.hpp"
#include "tests/fixtures.hpp"
#include "tests/repair_soups.hpp"

using namespace geotex;
using namespace geotex::test;

namespace {

// A repair on disk, with its faces read back, as a MeshRepairResult.
MeshRepairResult as_held_result(RepairedOnDisk disk) {
    MeshRepairResult r;
    const PositionSpan positions = disk.positions.positions();
    r.mesh.positions.assign(positions.begin(), positions.end());
    face_reader(disk.faces)(0, disk.num_faces, r.mesh.faces);
    CHECK(disk.faces.size() == 3 * disk.num_faces);
    r.report = disk.report;
    r.diagnostics = std::move(disk.diagnostics);
    return r;
}

// The repair on disk as a MeshRepairResult.
MeshRepairResult repaired_on_disk(PolygonSoup soup, MeshRepairParams params,
                                  const std::string& dir) {
    params.keep_sources = false;
    return as_held_result(repair_soup_on_disk(std::move(soup), params, dir));
}

// The repair on disk equals the repair held, with the same parameters.
void require_same_on_disk(const PolygonSoup& soup, MeshRepairParams params,
                          const std::string& dir) {
    params.keep_sources = false;
    require_same_repair(repair_soup(soup, params), repaired_on_disk(soup, params, dir));
}

// `soup` as a SoupOnDisk, its positions and polygons appended in `blocks` blocks, as a reader's
// sink gives them.
SoupOnDisk on_disk_in_blocks(const PolygonSoup& soup, int blocks, const std::string& dir) {
    SoupOnDisk out(dir);
    const int n = soup.num_polygons();
    const std::size_t nv = soup.positions.size();
    for (int b = 0; b < blocks; ++b) {
        const int first = n * b / blocks, last = n * (b + 1) / blocks;
        PolygonSoup block;
        for (int p = first; p < last; ++p) {
            block.face_indices.insert(block.face_indices.end(),
                                      soup.face_indices.begin() + soup.face_offsets[p],
                                      soup.face_indices.begin() + soup.face_offsets[p + 1]);
            block.face_offsets.push_back(static_cast<int>(block.face_indices.size()));
        }
        const auto share = [&](int k) {
            return static_cast<long>(nv * static_cast<std::size_t>(k) /
                                     static_cast<std::size_t>(blocks));
        };
        block.positions.assign(soup.positions.begin() + share(b),
                               soup.positions.begin() + share(b + 1));
        out.append(block);
    }
    return out;
}

// What repair_soup throws for `soup`.
std::string repair_error(const PolygonSoup& soup, const MeshRepairParams& params) {
    try {
        repair_soup(soup, params);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    FAIL("repair_soup took the soup");
    return {};
}

}  // namespace

TEST_CASE("scratch file: values appended come back from any place", "[geometry][mesh_repair]") {
    const TempDir dir("repair-disk");
    ScratchFile file(dir.path());
    CHECK(dir.empty());  // it has no name
    // More than the file's buffer, so that reads meet values written and values still held.
    std::vector<int> values(3'000'000);
    std::iota(values.begin(), values.end(), -7);
    file.append(values.data(), 1'500'001);
    file.append(values.data() + 1'500'001, values.size() - 1'500'001);
    REQUIRE(file.size() == values.size());
    for (std::size_t first : {std::size_t{0}, std::size_t{1'048'575}, std::size_t{2'999'990}}) {
        std::vector<int> out(10);
        file.read(first, 10, out.data());
        CHECK(out == std::vector<int>(values.begin() + static_cast<std::ptrdiff_t>(first),
                                      values.begin() + static_cast<std::ptrdiff_t>(first) + 10));
    }
    int one = 0;
    CHECK_THROWS_AS(file.read(values.size(), 1, &one), std::out_of_range);
    // Faces: three values each.
    std::vector<std::array<int, 3>> faces;
    face_reader(file)(2, 2, faces);
    CHECK(faces == std::vector<std::array<int, 3>>{{{-1, 0, 1}, {2, 3, 4}}});
    // Moved, the file goes with the object it is moved to.
    ScratchFile moved = std::move(file);
    moved.read(0, 1, &one);
    CHECK(one == -7);
    CHECK(dir.empty());
}

TEST_CASE("position file: positions appended are read through its mapping",
          "[geometry][mesh_repair]") {
    const TempDir dir("repair-disk");
    PositionFile file(dir.path());
    CHECK(file.positions().empty());  // nothing to map yet
    // More than the file's buffer (4 MB, 174,762 positions), so that a part was still held.
    std::vector<Eigen::Vector3d> positions;
    for (int v = 0; v < 400'000; ++v) positions.emplace_back(v, -0.5 * v, 1e300 / (v + 1));
    file.append(PositionSpan(positions.data(), 1000));
    for (std::size_t v = 1000; v < positions.size(); ++v) file.append(positions[v]);
    REQUIRE(file.size() == positions.size());
    const PositionSpan mapped = file.positions();
    REQUIRE(mapped.size() == positions.size());
    CHECK(std::equal(mapped.begin(), mapped.end(), positions.begin()));
    CHECK(file.positions().begin() == mapped.begin());  // mapped once
    // Nothing can be appended under the mapping; moved, the mapping goes with the file.
    CHECK_THROWS_AS(file.append(positions[0]), std::logic_error);
    PositionFile moved = std::move(file);
    CHECK(moved.positions().begin() == mapped.begin());
    CHECK(mapped[399'999] == positions[399'999]);
    CHECK(dir.empty());
}

namespace {

// Where each vertex's position lies in the copy of a SpaceOrderedPositions, which operator[]
// reads.
std::vector<std::ptrdiff_t> places_in_copy(PositionSpan span) {
    std::vector<const Eigen::Vector3d*> at;
    for (std::size_t v = 0; v < span.size(); ++v) at.push_back(&span[v]);
    const Eigen::Vector3d* first = *std::min_element(at.begin(), at.end());
    std::vector<std::ptrdiff_t> places;
    for (const Eigen::Vector3d* p : at) places.push_back(p - first);
    return places;
}

bool same_position(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()) && same_bits(a.z(), b.z());
}

}  // namespace

TEST_CASE("positions in the order of space: cells in Morton order, the same values",
          "[geometry][mesh_repair]") {
    const TempDir dir("space-order");
    SECTION("the corners of a cube: z's bit highest, then y's, then x's") {
        // Numbered from the last corner: corner k is (k & 1, k >> 1 & 1, k >> 2 & 1), in cell 0
        // or 127 of each axis, and Morton's interleaving puts it at place k.
        std::vector<Eigen::Vector3d> corners;
        for (int k = 7; k >= 0; --k) corners.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        const SpaceOrderedPositions ordered(corners, dir.path().string());
        const PositionSpan span = ordered.positions();
        REQUIRE(span.size() == 8);
        CHECK(places_in_copy(span) == std::vector<std::ptrdiff_t>{7, 6, 5, 4, 3, 2, 1, 0});
        for (std::size_t v = 0; v < 8; ++v) CHECK(same_position(span[v], corners[v]));
        // Iteration and in_order() read the positions given, in vertex order.
        CHECK(span.begin() == corners.data());
        CHECK(span.in_order()[3].data() == corners[3].data());
    }
    SECTION("points along a line, shuffled: by x, a cell's in vertex order, in any share") {
        // Two vertices at each x = 0 .. 127, one cell each along x; y and z have no extent.
        std::vector<int> xs;
        for (int x = 0; x < 128; ++x) xs.insert(xs.end(), {x, x});
        std::mt19937 rng(7);
        std::shuffle(xs.begin(), xs.end(), rng);
        std::vector<Eigen::Vector3d> points;
        for (int x : xs) points.emplace_back(x, 0.25, -3.0);
        std::vector<int> expected(points.size());  // vertex ids by place
        std::iota(expected.begin(), expected.end(), 0);
        std::stable_sort(expected.begin(), expected.end(),
                         [&](int a, int b) { return xs[a] < xs[b]; });
        for (std::size_t share : {std::size_t{128} << 20, 3 * sizeof(Eigen::Vector3d)}) {
            const SpaceOrderedPositions ordered(points, dir.path().string(), share);
            const PositionSpan span = ordered.positions();
            const std::vector<std::ptrdiff_t> places = places_in_copy(span);
            std::vector<int> by_place(points.size());
            for (std::size_t v = 0; v < points.size(); ++v)
                by_place.at(places[v]) = static_cast<int>(v);
            CHECK(by_place == expected);
            for (std::size_t v = 0; v < points.size(); ++v)
                CHECK(same_position(span[v], points[v]));
        }
    }
    CHECK(dir.empty());
}

TEST_CASE("scratch file: a directory it cannot be made in is named", "[geometry][mesh_repair]") {
    const TempDir dir("repair-disk");
    const std::string missing = (dir.path() / "no such directory").string();
    try {
        ScratchFile file(missing);
        FAIL("a scratch file was made in a missing directory");
    } catch (const IoError& e) {
        CHECK(e.file() == missing);
        CHECK_THAT(e.what(), Catch::Contains("cannot create a scratch file"));
    }
}

TEST_CASE("repair on disk: the same mesh, report and notes as the repair that holds the faces",
          "[geometry][mesh_repair]") {
    const TempDir dir("repair-disk");
    MeshRepairParams params;
    SECTION("every step of the repair, whole and in tiles") {
        for (int tiles : {1, 4, 9}) {
            INFO(tiles << " tiles");
            params.tiles = tiles;
            require_same_on_disk(every_step_soup(), params, dir.path());
            require_same_on_disk(own_corners_soup(mixed_scene()), params, dir.path());
        }
    }
    SECTION("what the tiles cannot tell is done holding the faces, as repair_soup does") {
        params.tiles = 4;
        require_same_on_disk(moebius_strip(40), params, dir.path());
    }
    SECTION("without orienting or merging") {
        params.tiles = 4;
        params.orient = false;
        require_same_on_disk(every_step_soup(), params, dir.path());
        params.merge_duplicate_vertices = false;
        require_same_on_disk(own_corners_soup(mixed_scene()), params, dir.path());
    }
    SECTION("polygons appended in blocks, as a reader gives them") {
        params.keep_sources = false;
        const PolygonSoup soup = own_corners_soup(mixed_scene());
        for (int tiles : {1, 4}) {
            params.tiles = tiles;
            const MeshRepairResult r = as_held_result(
                repair_soup_on_disk(on_disk_in_blocks(soup, 3, dir.path()), params, dir.path()));
            require_same_repair(repair_soup(soup, params), r);
        }
    }
    SECTION("a sphere with reversed faces, in many tiles") {
        params.tiles = 16;
        const PolygonSoup soup =
            own_corners_soup(randomly_flipped(test::make_sphere(1.0, 4), 0.4, 7));
        const MeshRepairResult r = repaired_on_disk(soup, params, dir.path());
        CHECK(r.report.num_faces_flipped > 0);
        require_same_on_disk(soup, params, dir.path());
    }
    SECTION("a mesh of more faces than the tiles asked for should hold, in more tiles") {
        // 5,120 faces, 4 tiles asked of at most 200 faces: 26 needed, oriented in 30 (5 x 6).
        params.tiles = 4;
        params.tile_faces = 200;
        const PolygonSoup soup =
            own_corners_soup(randomly_flipped(test::make_sphere(1.0, 4), 0.4, 11));
        REQUIRE(detail::orientation_tiles(5120, 4, 200) == 30);
        require_same_on_disk(soup, params, dir.path());
        require_same_on_disk(every_step_soup(), params, dir.path());
    }
    CHECK(dir.empty());  // the scratch files went with the repairs
}

TEST_CASE("repair on disk: the orientation's tiles, by the faces each should hold",
          "[geometry][mesh_repair]") {
    // Enough as asked, or one tile asked (the whole mesh): as asked.
    CHECK(detail::orientation_tiles(1000, 4, 250) == 4);
    CHECK(detail::orientation_tiles(1000, 16, 100) == 16);
    CHECK(detail::orientation_tiles(1000000, 1, 10) == 1);
    // More: the least k x (k + 1) or k x k at least the faces over the most a tile holds.
    CHECK(detail::orientation_tiles(1001, 4, 250) == 6);   // 5 needed: 2 x 3
    CHECK(detail::orientation_tiles(1000, 4, 100) == 12);  // 10: 3 x 4
    CHECK(detail::orientation_tiles(1300, 4, 100) == 16);  // 13: 4 x 4
    CHECK(detail::orientation_tiles(1700, 4, 100) == 20);  // 17: 4 x 5
    // Sphere-1 level 11 in 64 tiles of at most 2^18 faces: 320 needed, 18 x 18.
    CHECK(detail::orientation_tiles(83886080, 64, std::size_t{1} << 18) == 324);
    // A most of 0 is taken as 1 face a tile.
    CHECK(detail::orientation_tiles(30, 2, 0) == 30);
}

TEST_CASE("repair on disk: bad soups are refused as repair_soup refuses them",
          "[geometry][mesh_repair]") {
    const TempDir dir("repair-disk");
    MeshRepairParams params;
    params.keep_sources = false;
    params.tiles = 4;
    const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    const std::vector<Eigen::Vector3d> nan = {{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}};
    for (const PolygonSoup& soup : {make_soup(line, {{0, 1, 2}, {2, 1, 0}}),       // no area
                                    make_soup(line, {{0, 1, 3}}),                  // out of range
                                    make_soup(line, {{0, 1, 2}, {0, 1}, {1, 0}}),  // too small
                                    make_soup(line, {{0, 1, 2}, {0, -1, 2}, {1, 0}}),  // both
                                    make_soup(nan, {{0, 1, 2}}), make_soup(line, {})}) {
        const std::string whole = repair_error(soup, params);
        REQUIRE_FALSE(whole.empty());
        CHECK_THROWS_WITH(repair_soup_on_disk(PolygonSoup(soup), params, dir.path()), whole);
        // The polygons on disk are checked as the repair reads them, with the same words.
        CHECK_THROWS_WITH(
            repair_soup_on_disk(on_disk_in_blocks(soup, 2, dir.path()), params, dir.path()), whole);
    }
    // Offsets that do not fit their indices are refused as they are appended.
    PolygonSoup bad = make_soup(line, {{0, 1, 2}});
    bad.face_offsets.back() = 2;
    SoupOnDisk on_disk(dir.path());
    CHECK_THROWS_WITH(on_disk.append(bad), repair_error(bad, params));
    params.keep_sources = true;
    CHECK_THROWS_AS(repair_soup_on_disk(every_step_soup(), params, dir.path()),
                    std::invalid_argument);
    CHECK(dir.empty());
}

TEST_CASE("face reader: faces held are read a block at a time", "[geometry][mesh_repair]") {
    const std::vector<std::array<int, 3>> held = {{0, 1, 2}, {2, 1, 3}, {3, 4, 5}};
    const FaceBlockReader read = face_reader(held);
    std::vector<std::array<int, 3>> out;
    read(1, 2, out);
    CHECK(out == std::vector<std::array<int, 3>>{{{2, 1, 3}, {3, 4, 5}}});
    read(3, 0, out);
    CHECK(out.empty());
    CHECK_THROWS_AS(read(2, 2, out), std::out_of_range);
    CHECK_THROWS_AS(read(4, 0, out), std::out_of_range);
}
