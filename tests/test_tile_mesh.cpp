// A tile's mesh for the first depth pass on disk (pipeline/tile_mesh.hpp, made by `--pass
// mesh`): read back bit for bit, giving the depth part that the job holding the whole mesh
// gives, and refused, saying why, when it is another run's or tile's, or damaged.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/segmentation_steps.hpp"
#include "geometry/detail/tile_steps.hpp"
#include "geometry/rims.hpp"
#include "geometry/texels.hpp"
#include "geometry/tile_alone.hpp"
#include "pipeline/sorted_depths.hpp"
#include "pipeline/tile_mesh.hpp"
#include "pipeline/tile_parts.hpp"
#include "tests/fixtures.hpp"
#include "tests/sparql_test_support.hpp"

using namespace geotex;
using sparql_test::TempFile;
using test::same_bits;

namespace {

std::string bytes_of(const std::string& key, const DepthTile& tile) {
    std::ostringstream out;
    write_tile_mesh(out, key, tile);
    return out.str();
}

// A part's bytes on disk: two parts with the same bytes are the same part.
std::string write_part_bytes(const TilePart& part) {
    std::ostringstream out;
    write_tile_part(out, "key", part);
    return out.str();
}

DepthTile read_back(const std::string& bytes, const std::string& key, int tile) {
    std::istringstream in(bytes);
    return read_tile_mesh(in, key, tile);
}

std::string refused(const std::string& bytes, const std::string& key, int tile) {
    try {
        read_back(bytes, key, tile);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "(read)";
}

// Where the arrays start: after the magic line (17 bytes), the header's length and the header.
std::size_t arrays_start(const std::string& bytes) {
    std::uint64_t length = 0;
    for (int k = 0; k < 8; ++k)
        length |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[17 + k])) << (8 * k);
    return 25 + length;
}

// Bitwise equality of two doubles.

// Whether two depth parts give the same depths, bit for bit, and the same moved counts.
bool same_depths(const TilePart& a, const TilePart& b) {
    if (a.depths.size() != b.depths.size() || a.moved != b.moved) return false;
    for (std::size_t i = 0; i < a.depths.size(); ++i) {
        if (a.depths[i].size() != b.depths[i].size()) return false;
        for (std::size_t k = 0; k < a.depths[i].size(); ++k)
            if (!same_bits(a.depths[i][k], b.depths[i][k])) return false;
    }
    return true;
}

SegmentationParams fast_params() {
    SegmentationParams p;
    p.radius_rel = 0.04;
    p.disc = DiscMode::Fast;  // so that the sampling's flags and grid matter
    return p;
}

}  // namespace

TEST_CASE("a tile's mesh read back gives the depth part of the job that holds the whole mesh",
          "[tiles]") {
    const Mesh m = test::half_engraved_sphere(6);
    const SegmentationParams p = fast_params();
    const TiledSegmentation run(m, p, 4);
    int sampled = 0;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const DepthTile made = run.depth_tile(b);
        const DepthTile tile = read_back(bytes_of("k", made), "k", b);
        CHECK(tile.tile == b);
        CHECK(tile.boxes.count == made.boxes.count);
        CHECK(tile.boxes.size() == 4);
        for (int k = 0; k < 3; ++k) {
            CHECK(same_bits(tile.boxes.lo[k], made.boxes.lo[k]));
            CHECK(same_bits(tile.boxes.hi[k], made.boxes.hi[k]));
        }
        CHECK(tile.mesh_vertices == m.num_vertices());
        CHECK(same_bits(tile.radius, made.radius));
        CHECK(same_bits(tile.halo, made.halo));
        CHECK(tile.halo == kTileMeshHaloRadii * made.radius);
        CHECK(tile.mesh.mesh.faces == made.mesh.mesh.faces);
        REQUIRE(tile.mesh.mesh.positions.size() == made.mesh.mesh.positions.size());
        for (std::size_t v = 0; v < tile.mesh.mesh.positions.size(); ++v)
            for (int k = 0; k < 3; ++k)
                CHECK(same_bits(tile.mesh.mesh.positions[v][k], made.mesh.mesh.positions[v][k]));
        CHECK(tile.mesh.vertex == made.mesh.vertex);
        CHECK(tile.mesh.face == made.mesh.face);
        CHECK(tile.mesh.owned_vertex == made.mesh.owned_vertex);
        CHECK(tile.mesh.owned_face == made.mesh.owned_face);
        CHECK(tile.mesh.complete_vertex == made.mesh.complete_vertex);
        CHECK(tile.sampling.fast == made.sampling.fast);
        CHECK(tile.sampling.grid == made.sampling.grid);
        for (int k = 0; k < 3; ++k)
            CHECK(same_bits(tile.sampling.origin[k], made.sampling.origin[k]));
        CHECK(tile.components.component == made.components.component);
        CHECK(tile.components.num_components == made.components.num_components);
        for (char f : tile.sampling.fast) sampled += f;

        // The part from the tile alone is the part of the run that holds the whole mesh.
        const TilePart alone = first_depth_part(tile, p);
        const TilePart whole = run.run_tile(b);
        CHECK(alone.pass == TilePass::Depth);
        CHECK(alone.tile == b);
        CHECK(alone.vertices == whole.vertices);
        CHECK(alone.depths.size() == 2);  // both orientations: rims are removed
        CHECK(same_depths(alone, whole));
        CHECK(alone.interpolated == whole.interpolated);
        CHECK(alone.samples == whole.samples);
    }
    CHECK(sampled > 0);  // the fast mode sampled some discs: the flags were carried
}

TEST_CASE("a tile's mesh of another run or tile, or a damaged one, is refused, saying why",
          "[tiles]") {
    const Mesh m = test::make_sphere(1.5, 3);
    const TiledSegmentation run(m, fast_params(), 4);
    const DepthTile tile = run.depth_tile(1);
    const std::string good = bytes_of("k1", tile);
    REQUIRE(refused(good, "k1", 1) == "(read)");
    const std::size_t nv = tile.mesh.mesh.positions.size(), nf = tile.mesh.mesh.faces.size();
    const std::size_t start = arrays_start(good);
    CHECK(good.size() == start + 33 * nv + 17 * nf);

    CHECK_THAT(refused(good, "k2", 1), Catch::Contains("the tile mesh of another run"));
    CHECK_THAT(refused(good, "k1", 2), Catch::Contains("the mesh of tile 2, not of tile 3"));
    CHECK_THAT(refused("", "k1", 1), Catch::Contains("not a geotex tile mesh"));
    CHECK_THAT(refused(good.substr(0, 20), "k1", 1), Catch::Contains("ends in its header"));
    CHECK_THAT(refused(good.substr(0, good.size() - 1), "k1", 1),
               Catch::Contains("ends inside its arrays"));
    CHECK_THAT(refused(good + "x", "k1", 1), Catch::Contains("bytes past the end"));

    // Each array's bytes spoiled in turn.
    const auto spoiled = [&](std::size_t at, const std::string& bytes) {
        std::string s = good;
        s.replace(at, bytes.size(), bytes);
        return refused(s, "k1", 1);
    };
    const std::string nan_bits = [] {
        const double x = std::numeric_limits<double>::quiet_NaN();
        return std::string(reinterpret_cast<const char*>(&x), 8);
    }();
    CHECK_THAT(spoiled(start + 8, nan_bits), Catch::Contains("vertex 0 has a coordinate"));
    const std::size_t ids = start + 24 * nv;
    CHECK_THAT(spoiled(ids + 4, std::string(4, '\0')),
               Catch::Contains("the ids of its vertices do not ascend"));
    const std::size_t flags = ids + 4 * nv;
    CHECK_THAT(spoiled(flags + 2, "\x08"), Catch::Contains("vertex 2's flags are unknown"));
    const std::size_t components = flags + nv;
    CHECK_THAT(spoiled(components + 4, std::string("\xff\xff\x00\x00", 4)),
               Catch::Contains("vertex 1's component is out of range"));
    const std::size_t faces = components + 4 * nv;
    CHECK_THAT(spoiled(faces + 12, std::string("\xff\xff\xff\x00", 4)),
               Catch::Contains("face 1 names a vertex past the last"));
    const std::size_t face_ids = faces + 12 * nf;
    CHECK_THAT(spoiled(face_ids + 4 * (nf - 1), std::string(4, '\0')),
               Catch::Contains("the ids of its faces do not ascend"));
    CHECK_THAT(spoiled(face_ids + 4 * nf, "\x02"), Catch::Contains("face 0's flags are unknown"));
}

TEST_CASE("a depth part is refused a tile whose arrays do not fit its vertices", "[tiles]") {
    const Mesh m = test::make_sphere(1.5, 3);
    const SegmentationParams p = fast_params();
    const TiledSegmentation run(m, p, 4);
    DepthTile tile = run.depth_tile(0);
    tile.sampling.fast.pop_back();
    CHECK_THROWS_WITH(first_depth_part(tile, p), Catch::Contains("sampling or components"));
    tile = run.depth_tile(0);
    tile.tile = 4;
    CHECK_THROWS_WITH(first_depth_part(tile, p), Catch::Contains("not one of the run's tiles"));
    tile = run.depth_tile(0);
    tile.components.component[0] = tile.components.num_components;
    CHECK_THROWS_WITH(first_depth_part(tile, p), Catch::Contains("component is out of range"));
    tile = run.depth_tile(0);
    tile.halo = 5 * tile.radius;
    CHECK_THROWS_WITH(first_depth_part(tile, p), Catch::Contains("halo is narrower"));
    CHECK_THROWS_WITH(run.depth_tile(4), Catch::Contains("tile 5 is not in 1 to 4"));
}

namespace {

// Every tile's part of the first depth pass, joined into `run`, which then waits for the
// texels.
std::vector<TilePart> depth_parts(TiledSegmentation& run) {
    std::vector<TilePart> parts;
    for (int b = 0; b < run.num_tiles(); ++b) parts.push_back(run.run_tile(b));
    for (const TilePart& part : parts) run.add(part);
    run.finish_pass();
    return parts;
}

bool same_regions(const std::vector<TexelRegions>& a, const std::vector<TexelRegions>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].num_seeds != b[i].num_seeds || a[i].regions.size() != b[i].regions.size())
            return false;
        for (std::size_t k = 0; k < a[i].regions.size(); ++k) {
            const TexelRegion &x = a[i].regions[k], &y = b[i].regions[k];
            if (x.seed != y.seed || !same_bits(x.threshold, y.threshold) ||
                !same_bits(x.mean, y.mean) || !same_bits(x.std, y.std) || x.faces != y.faces ||
                x.touch != y.touch)
                return false;
        }
    }
    return true;
}

}  // namespace

TEST_CASE("a tile's texel part made from its mesh and the depth parts is the whole run's",
          "[tiles]") {
    Mesh m = test::half_engraved_sphere(6);
    // A vertex on no face: in no tile and no part, but a zero depth of the joined maps, which
    // Otsu counts.
    m.positions.push_back(Eigen::Vector3d::Zero());
    SegmentationParams p = fast_params();
    p.orientation = OrientationMode::Both;
    TiledSegmentation run(m, p, 4);
    const std::vector<TilePart> parts = depth_parts(run);
    REQUIRE(run.pass() == TilePass::Texels);
    int reads = 0;
    const TilePartSource part_of = [&](int k) {
        ++reads;
        return parts[static_cast<std::size_t>(k)];
    };
    const DepthTile first = run.depth_tile(0);
    const std::vector<double> thresholds = texel_thresholds(first, p, first_depth_pass(p), part_of);
    CHECK(reads == 4);  // each part once, for both orientations
    // Otsu over the joined maps, the isolated vertex's zero among them.
    REQUIRE(thresholds.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
        std::vector<double> joined(m.positions.size(), 0.0);
        for (const TilePart& part : parts)
            for (std::size_t k = 0; k < part.vertices.size(); ++k)
                joined[part.vertices[k]] = part.depths[i][k];
        CHECK(same_bits(thresholds[i],
                        texel_global_threshold(joined, detail::texel_params(p, first.radius))));
    }
    // The same bits merged from every tile's sorted depths, written and read back as the jobs
    // do (a job merges them instead of holding every vertex's depth).
    std::vector<std::unique_ptr<TempFile>> files;
    for (const TilePart& part : parts) {
        std::ostringstream out;
        write_sorted_depths(out, "key", part);
        files.push_back(std::make_unique<TempFile>("tile.sorted", out.str()));
    }
    int opened = 0;
    const SortedDepthSource sorted_of = [&](int k, std::size_t i) {
        ++opened;
        return SortedDepthsFile(files[static_cast<std::size_t>(k)]->path(), "key", TilePass::Depth,
                                k)
            .values(i);
    };
    const std::vector<double> merged =
        texel_thresholds_merged(first, p, first_depth_pass(p), sorted_of);
    CHECK(opened == 8);  // each tile's file, each orientation
    REQUIRE(merged.size() == 2);
    CHECK(same_bits(merged[0], thresholds[0]));
    CHECK(same_bits(merged[1], thresholds[1]));
    int seeds = 0;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const DepthTile tile = run.depth_tile(b);
        const std::vector<std::vector<double>> depths =
            depths_in_tile(tile, p, first_depth_pass(p), part_of);
        const std::optional<TilePart> alone =
            texel_part_in_tile(tile, depths, thresholds, p, first_depth_pass(p));
        REQUIRE(alone);
        const TilePart whole = run.run_tile(b);
        CHECK(alone->pass == TilePass::Texels);
        CHECK(alone->tile == b);
        CHECK(same_regions(alone->regions, whole.regions));
        for (const TexelRegions& r : alone->regions) seeds += r.num_seeds;
    }
    CHECK(seeds > 0);  // the parts held texels to compare
}

TEST_CASE("a tile's depths come from the parts of the tiles its vertices lie in, no others",
          "[tiles]") {
    // A square in 4 x 4 tiles with a halo of 12r = 0.36: a corner tile reaches 3 x 3 boxes.
    const Mesh m = test::make_grid(120, 1.0, [](double x, double y) {
        return 0.005 *
               std::exp(-((x - 0.2) * (x - 0.2) + (y - 0.3) * (y - 0.3)) / (2 * 0.03 * 0.03));
    });
    SegmentationParams p = fast_params();
    p.radius_rel = 0.03;
    TiledSegmentation run(m, p, 16);
    REQUIRE(run.num_tiles() == 16);
    const std::vector<TilePart> parts = depth_parts(run);
    // Every vertex's depths, from every part.
    const std::size_t n = first_depth_pass(p).orientations.size();
    std::vector<std::vector<double>> depth_of(n, std::vector<double>(m.positions.size(), -1.0));
    for (const TilePart& part : parts)
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < part.vertices.size(); ++j)
                depth_of[i][static_cast<std::size_t>(part.vertices[j])] = part.depths[i][j];
    int fewest = 16;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const DepthTile tile = run.depth_tile(b);
        int reads = 0;
        const TilePartSource part_of = [&](int k) {
            ++reads;
            return parts[static_cast<std::size_t>(k)];
        };
        const std::vector<std::vector<double>> depths =
            depths_in_tile(tile, p, first_depth_pass(p), part_of);
        REQUIRE(depths.size() == n);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t a = 0; a < tile.mesh.vertex.size(); ++a)
                CHECK(same_bits(depths[i][a],
                                depth_of[i][static_cast<std::size_t>(tile.mesh.vertex[a])]));
        fewest = std::min(fewest, reads);
    }
    CHECK(fewest == 9);  // a corner tile: its box and those beside it, 3 x 3 of the 16
}

TEST_CASE("a texel larger than a tile's halo sends its tile to the whole mesh", "[tiles]") {
    // A thin ridge across a square, 50r long: its texel crosses the tiles, past any 6r halo.
    const Mesh m = test::make_grid(200, 1.0, [](double x, double) {
        return 0.01 * std::exp(-(x - 0.3) * (x - 0.3) / (2 * 0.01 * 0.01));
    });
    SegmentationParams p = fast_params();
    p.radius_rel = 0.02;
    TiledSegmentation run(m, p, 4);
    const std::vector<TilePart> parts = depth_parts(run);
    const TilePartSource part_of = [&](int k) { return parts[static_cast<std::size_t>(k)]; };
    const std::vector<double> thresholds =
        texel_thresholds(run.depth_tile(0), p, first_depth_pass(p), part_of);
    int outgrown = 0;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const DepthTile tile = run.depth_tile(b);
        const std::optional<TilePart> alone =
            texel_part_in_tile(tile, depths_in_tile(tile, p, first_depth_pass(p), part_of),
                               thresholds, p, first_depth_pass(p));
        if (!alone)
            ++outgrown;
        else
            CHECK(same_regions(alone->regions, run.run_tile(b).regions));
    }
    CHECK(outgrown > 0);
}

TEST_CASE("sorted depths of another run, pass or tile, or damaged, are refused, naming the file",
          "[tiles]") {
    const Mesh m = test::half_engraved_sphere(5);
    SegmentationParams p = fast_params();
    p.orientation = OrientationMode::Both;
    TiledSegmentation run(m, p, 4);
    const std::vector<TilePart> parts = depth_parts(run);
    std::ostringstream out;
    write_sorted_depths(out, "key", parts[1]);
    const std::string bytes = out.str();
    const TempFile good("tile-2.sorted", bytes);
    const SortedDepthsFile file(good.path(), "key", TilePass::Depth, 1);
    REQUIRE(file.orientations() == parts[1].depths.size());
    // Its values are the part's, ascending.
    std::vector<double> expected = parts[1].depths[0];
    std::sort(expected.begin(), expected.end());
    std::vector<double> read(expected.size() + 5);
    const std::unique_ptr<SortedValues> values = file.values(0);
    REQUIRE(values->size() == expected.size());
    CHECK(values->next(read.data(), read.size()) == expected.size());
    read.resize(expected.size());
    CHECK(read == expected);
    CHECK(file.greatest()[0] == expected.back());
    const auto refusal = [&](const std::string& content, const std::string& key, TilePass pass,
                             int tile) {
        const TempFile f("tile.sorted", content);
        try {
            SortedDepthsFile(f.path(), key, pass, tile);
        } catch (const InvalidInput& e) {
            CHECK(e.file() == f.path());
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK_THAT(refusal(bytes, "other", TilePass::Depth, 1), Catch::Contains("of another run"));
    CHECK_THAT(refusal(bytes, "key", TilePass::Depth, 2),
               Catch::Contains("of pass depth, tile 2, not of pass depth, tile 3"));
    CHECK_THAT(refusal(bytes, "key", TilePass::DepthWithoutRims, 1),
               Catch::Contains("not of pass depth-without-rims"));
    CHECK_THAT(refusal(bytes.substr(0, bytes.size() - 4), "key", TilePass::Depth, 1),
               Catch::Contains("the file ends inside its arrays"));
    CHECK_THAT(refusal(bytes + "x", "key", TilePass::Depth, 1),
               Catch::Contains("bytes past the end"));
    CHECK_THAT(refusal("ply\n", "key", TilePass::Depth, 1),
               Catch::Contains("not a geotex sorted depths file"));
    // Depths that do not ascend are refused by the merge, naming the file: the two greatest
    // depths of the first orientation swapped.
    REQUIRE(file.orientations() == 2);
    const std::size_t n0 = parts[1].depths[0].size(), n1 = parts[1].depths[1].size();
    REQUIRE(n0 >= 2);
    REQUIRE(expected[n0 - 2] < expected[n0 - 1]);
    std::string swapped = bytes;
    const long at = static_cast<long>(bytes.size() - 8 * (n0 + n1) + 8 * (n0 - 2));
    std::swap_ranges(swapped.begin() + at, swapped.begin() + at + 8, swapped.begin() + at + 8);
    const TempFile f("tile.sorted", swapped);
    const SortedDepthsFile damaged(f.path(), "key", TilePass::Depth, 1);
    const std::unique_ptr<SortedValues> v = damaged.values(0);
    try {
        otsu_threshold_merged({v.get()});
        FAIL("descending depths accepted");
    } catch (const InvalidInput& e) {
        CHECK(e.file() == f.path());
        CHECK_THAT(e.what(), Catch::Contains("is not ascending"));
    }
    CHECK_THROWS_WITH(damaged.values(2), Catch::Contains("orientations, not 3"));
    TilePart texels;
    texels.pass = TilePass::Texels;
    CHECK_THROWS_WITH(write_sorted_depths(out, "key", texels),
                      Catch::Contains("pass texels is not a depth pass"));

    // The seeds' thresholds a texel job leaves: read back bit for bit, infinite (no split)
    // included; another run's, pass's or count is refused.
    std::ostringstream left;
    const std::vector<double> thresholds = {0.0125, std::numeric_limits<double>::infinity()};
    write_seed_thresholds(left, "key", TilePass::Texels, thresholds);
    const auto read_thresholds = [&](const std::string& key, TilePass pass, std::size_t n) {
        std::istringstream in(left.str());
        return read_seed_thresholds(in, key, pass, n);
    };
    const std::vector<double> back = read_thresholds("key", TilePass::Texels, 2);
    REQUIRE(back.size() == 2);
    CHECK(same_bits(back[0], thresholds[0]));
    CHECK(same_bits(back[1], thresholds[1]));
    CHECK_THROWS_WITH(read_thresholds("other", TilePass::Texels, 2),
                      Catch::Contains("of another run"));
    CHECK_THROWS_WITH(read_thresholds("key", TilePass::TexelsWithoutRims, 2),
                      Catch::Contains("of pass texels, not of pass texels-without-rims"));
    CHECK_THROWS_WITH(read_thresholds("key", TilePass::Texels, 1),
                      Catch::Contains("2 thresholds for 1 orientations"));
}

TEST_CASE("depth parts that do not fit a tile are refused, saying why", "[tiles]") {
    const Mesh m = test::make_sphere(1.5, 3);
    const SegmentationParams p = fast_params();
    TiledSegmentation run(m, p, 4);
    std::vector<TilePart> parts = depth_parts(run);
    const DepthTile tile = run.depth_tile(1);
    const auto with = [&](const std::vector<TilePart>& given) {
        return TilePartSource([given](int k) { return given[static_cast<std::size_t>(k)]; });
    };
    std::vector<TilePart> swapped = parts;
    std::swap(swapped[0], swapped[1]);
    CHECK_THROWS_WITH(texel_thresholds(tile, p, first_depth_pass(p), with(swapped)),
                      Catch::Contains("tile 1's part of pass depth does not fit this run: it is "
                                      "the part of another pass or tile"));
    // A vertex owned by two tiles: one depth too many for the mesh.
    std::vector<TilePart> owned_twice = parts;
    std::size_t big = 0;
    for (std::size_t k = 1; k < parts.size(); ++k)
        if (parts[k].vertices.size() > parts[big].vertices.size()) big = k;
    const std::size_t small = big == 0 ? 1 : 0;
    owned_twice[small].vertices = parts[big].vertices;
    owned_twice[small].depths = parts[big].depths;
    REQUIRE(parts[big].vertices.size() > parts[small].vertices.size());
    CHECK_THROWS_WITH(texel_thresholds(tile, p, first_depth_pass(p), with(owned_twice)),
                      Catch::Contains("the parts of pass depth give more depths than the mesh "
                                      "has vertices"));
    std::vector<TilePart> short_of_one = parts;
    short_of_one[1].vertices.pop_back();
    for (auto& d : short_of_one[1].depths) d.pop_back();
    CHECK_THROWS_WITH(depths_in_tile(tile, p, first_depth_pass(p), with(short_of_one)),
                      Catch::Contains("vertices of tile 2 their depth"));
    std::vector<TilePart> one_orientation = parts;
    one_orientation[2].depths.pop_back();
    one_orientation[2].moved.pop_back();
    CHECK_THROWS_WITH(depths_in_tile(tile, p, first_depth_pass(p), with(one_orientation)),
                      Catch::Contains("depths of 1 orientations, not 2"));
    const std::vector<double> thresholds =
        texel_thresholds(tile, p, first_depth_pass(p), with(parts));
    CHECK_THROWS_WITH(texel_part_in_tile(tile, {}, thresholds, p, first_depth_pass(p)),
                      Catch::Contains("do not fit its vertices"));
}

namespace {

// The first depth and texel passes of `run`, every tile's part made by the run, the texel
// parts written and read back as a job reads them; the run then waits for the rims.
std::vector<TilePart> texel_parts(TiledSegmentation& run, const std::string& key) {
    depth_parts(run);
    std::vector<TilePart> parts;
    for (int b = 0; b < run.num_tiles(); ++b) {
        std::ostringstream out;
        write_tile_part(out, key, run.run_tile(b));
        parts.push_back(read_tile_part(out.str(), key, TilePass::Texels, b));
    }
    for (const TilePart& part : parts) run.add(part);
    run.finish_pass();
    return parts;
}

}  // namespace

TEST_CASE(
    "the texels and rims joined from their parts, and the parts of the rims and the second "
    "smoothing made from a tile, are the whole run's",
    "[tiles]") {
    const Mesh m = test::half_engraved_sphere(6);
    SegmentationParams p = fast_params();
    p.orientation = OrientationMode::Both;
    TiledSegmentation run(m, p, 4);
    const std::vector<TilePart> parts = texel_parts(run, "k");
    REQUIRE(run.pass() == TilePass::Rims);
    const TilePartSource part_of = [&](int k) { return parts[static_cast<std::size_t>(k)]; };
    const DepthTile first = run.depth_tile(0);
    const JoinedTexels joined = join_texels(first, p, first_depth_pass(p), part_of);
    CHECK(rims_needed(joined, p));

    // Against the merge over joined depth maps, as the run that holds the whole mesh merges.
    TiledSegmentation again(m, p, 4);
    const std::vector<TilePart> depths = depth_parts(again);
    const TexelParams tp = detail::texel_params(p, first.radius);
    for (std::size_t i = 0; i < 2; ++i) {
        DepthMap map;
        map.orientation = i == 0 ? DetailOrientation::Positive : DetailOrientation::Negative;
        map.vertex_depth.assign(m.positions.size(), 0.0);
        for (const TilePart& part : depths)
            for (std::size_t k = 0; k < part.vertices.size(); ++k)
                map.vertex_depth[part.vertices[k]] = part.depths[i][k];
        set_face_depths(m, map);
        TexelRegions all;
        for (const TilePart& part : parts) {
            for (const TexelRegion& r : part.regions[i].regions) all.regions.push_back(r);
            all.num_seeds += part.regions[i].num_seeds;
        }
        const double threshold = texel_global_threshold(map.vertex_depth, tp);
        const TexelSet whole = detail::merge_tile_regions(all, map, tp, threshold);
        const TexelSet& alone = joined.texels[i];
        REQUIRE(alone.texels.size() == whole.texels.size());
        CHECK(alone.texels.size() >= 5);
        for (std::size_t t = 0; t < whole.texels.size(); ++t) {
            const Texel &a = alone.texels[t], &w = whole.texels[t];
            CHECK(a.faces == w.faces);
            CHECK(a.seed == w.seed);
            CHECK(a.orientation == w.orientation);
            CHECK(same_bits(a.threshold, w.threshold));
            CHECK(same_bits(a.depth_mean, w.depth_mean));
            CHECK(same_bits(a.depth_std, w.depth_std));
        }
        CHECK(same_bits(alone.global_threshold, whole.global_threshold));
        CHECK(alone.num_local_maxima == whole.num_local_maxima);
        CHECK(alone.num_regions == whole.num_regions);
        CHECK(alone.num_merges == whole.num_merges);
        CHECK(alone.diagnostics.size() == whole.diagnostics.size());
        CHECK(alone.face_texel.empty());
        const std::vector<double> peak = texel_depths(m, whole, map);
        REQUIRE(joined.depth[i].size() == peak.size());
        for (std::size_t t = 0; t < peak.size(); ++t) CHECK(same_bits(joined.depth[i][t], peak[t]));
    }

    // Each tile's rims part from its mesh and the joined texels.
    int rims = 0;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const TilePart alone = rims_part(run.depth_tile(b), joined, p);
        const TilePart whole = run.run_tile(b);
        CHECK(alone.pass == TilePass::Rims);
        CHECK(alone.tile == b);
        CHECK(alone.rims.positive_rim == whole.rims.positive_rim);
        CHECK(alone.rims.negative_rim == whole.rims.negative_rim);
        CHECK(alone.rims.positive_makes_rim == whole.rims.positive_makes_rim);
        CHECK(alone.rims.negative_makes_rim == whole.rims.negative_makes_rim);
        for (char f : alone.rims.positive_rim) rims += f;
    }
    CHECK(rims > 0);  // the engravings' lips are rims: there were flags to compare

    SegmentationParams kept = p;
    kept.remove_rims = false;
    CHECK_FALSE(rims_needed(joined, kept));

    // The second smoothing: the rims joined from their parts, then each tile's depth part and
    // texel part without the rims.
    std::vector<TilePart> rim_parts;
    for (int b = 0; b < run.num_tiles(); ++b) rim_parts.push_back(run.run_tile(b));
    const JoinedRims rims_joined =
        join_rims(first, joined, p, [&](int k) { return rim_parts[static_cast<std::size_t>(k)]; });
    for (const TilePart& part : rim_parts) run.add(part);
    run.finish_pass();
    REQUIRE(run.pass() == TilePass::DepthWithoutRims);
    CHECK(rims_joined.second.pass == TilePass::DepthWithoutRims);
    CHECK(rims_joined.second.orientations == run.orientations());
    // The same decision from the rims parts alone, without the joined texels.
    const JoinedRims rims_alone = join_rims_alone(
        run.num_tiles(), p, [&](int k) { return rim_parts[static_cast<std::size_t>(k)]; });
    CHECK(rims_alone.second.pass == TilePass::DepthWithoutRims);
    CHECK(rims_alone.second.orientations == rims_joined.second.orientations);
    CHECK(rims_alone.use == rims_joined.use);
    std::vector<TilePart> second;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const TilePart alone = depth_without_rims_part(run.depth_tile(b), joined, rims_joined, p);
        const TilePart whole = run.run_tile(b);
        CHECK(alone.pass == TilePass::DepthWithoutRims);
        CHECK(alone.vertices == whole.vertices);
        CHECK(same_depths(alone, whole));
        second.push_back(whole);
    }
    for (const TilePart& part : second) run.add(part);
    run.finish_pass();
    REQUIRE(run.pass() == TilePass::TexelsWithoutRims);
    const TilePartSource second_of = [&](int k) { return second[static_cast<std::size_t>(k)]; };
    std::vector<TilePart> third;
    const std::vector<double> thresholds =
        texel_thresholds(first, p, rims_joined.second, second_of);
    for (int b = 0; b < run.num_tiles(); ++b) {
        const DepthTile tile = run.depth_tile(b);
        const std::optional<TilePart> alone =
            texel_part_in_tile(tile, depths_in_tile(tile, p, rims_joined.second, second_of),
                               thresholds, p, rims_joined.second);
        REQUIRE(alone);
        const TilePart whole = run.run_tile(b);
        CHECK(alone->pass == TilePass::TexelsWithoutRims);
        CHECK(same_regions(alone->regions, whole.regions));
        CHECK(alone->thresholds == whole.thresholds);
        third.push_back(whole);
    }

    // The features: the segmentation's texels from both texel passes, and each tile's part
    // with the depths of the last depth pass of each orientation.
    const JoinedTexels second_texels = join_texels(
        first, p, rims_joined.second, [&](int k) { return third[static_cast<std::size_t>(k)]; });
    const std::vector<Texel> all = segmentation_texels(joined, second_texels, rims_joined, p);
    for (const TilePart& part : third) run.add(part);
    run.finish_pass();
    REQUIRE(run.pass() == TilePass::Features);
    std::array<DepthSource, 2> sources;
    for (std::size_t i = 0; i < 2; ++i) {
        const std::vector<DetailOrientation>& again = rims_joined.second.orientations;
        const DetailOrientation o =
            i == 0 ? DetailOrientation::Positive : DetailOrientation::Negative;
        if (std::find(again.begin(), again.end(), o) != again.end())
            sources[i] = {rims_joined.second, second_of, {}};
        else
            sources[i] = {first_depth_pass(p),
                          [&](int k) { return depths[static_cast<std::size_t>(k)]; },
                          {}};
    }
    // The greatest depths given, as a job takes them from the sorted depths' headers, rather
    // than read from every part: the same part.
    const auto greatest_of = [](const std::vector<TilePart>& of_pass) {
        std::vector<double> greatest(of_pass.front().depths.size(), 0.0);
        for (const TilePart& part : of_pass) {
            std::ostringstream out;
            write_sorted_depths(out, "key", part);
            const TempFile file("tile.sorted", out.str());
            const SortedDepthsFile sorted(file.path(), "key", part.pass, part.tile);
            for (std::size_t i = 0; i < greatest.size(); ++i)
                greatest[i] = std::max(greatest[i], sorted.greatest()[i]);
        }
        return greatest;
    };
    std::array<DepthSource, 2> given = sources;
    for (DepthSource& source : given)
        source.greatest = greatest_of(source.pass.pass == TilePass::Depth ? depths : second);
    CHECK(given[0].greatest.size() == given[0].pass.orientations.size());
    int rows = 0;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const std::optional<TilePart> alone = features_part(run.depth_tile(b), all, sources, p);
        REQUIRE(alone);
        const std::optional<TilePart> with_greatest =
            features_part(run.depth_tile(b), all, given, p);
        REQUIRE(with_greatest);
        CHECK(write_part_bytes(*with_greatest) == write_part_bytes(*alone));
        const TilePart whole = run.run_tile(b);
        CHECK(alone->pass == TilePass::Features);
        CHECK(alone->texels == whole.texels);
        REQUIRE(alone->rows.values.rows() == whole.rows.values.rows());
        for (Eigen::Index r = 0; r < whole.rows.values.rows(); ++r)
            for (Eigen::Index c = 0; c < whole.rows.values.cols(); ++c)
                CHECK(same_bits(alone->rows.values(r, c), whole.rows.values(r, c)));
        CHECK(alone->rows.no_contour == whole.rows.no_contour);
        CHECK(alone->rows.no_curvature == whole.rows.no_curvature);
        CHECK(alone->rows.diameters.size() == whole.rows.diameters.size());
        CHECK(alone->curvature_vertices == whole.curvature_vertices);
        REQUIRE(alone->curvature.curvedness.size() == whole.curvature.curvedness.size());
        for (std::size_t v = 0; v < whole.curvature.curvedness.size(); ++v)
            CHECK(same_bits(alone->curvature.curvedness[v], whole.curvature.curvedness[v]));
        rows += static_cast<int>(whole.rows.values.rows());
    }
    CHECK(rows >= 10);  // texels of both orientations had rows to compare
    // A depth part of the first pass is not one of the second.
    CHECK_THROWS_WITH(texel_thresholds(first, p, rims_joined.second,
                                       [&](int k) { return parts[static_cast<std::size_t>(k)]; }),
                      Catch::Contains("part of pass depth-without-rims does not fit"));
}

TEST_CASE("texel parts that do not fit each other are refused, saying why", "[tiles]") {
    const Mesh m = test::half_engraved_sphere(5);
    SegmentationParams p = fast_params();
    p.radius_rel = 0.05;
    p.orientation = OrientationMode::Both;
    TiledSegmentation run(m, p, 4);
    const std::vector<TilePart> parts = texel_parts(run, "k");
    const DepthTile tile = run.depth_tile(0);
    const auto join = [&](const std::vector<TilePart>& given) {
        return join_texels(tile, p, first_depth_pass(p),
                           [given](int k) { return given[static_cast<std::size_t>(k)]; });
    };
    CHECK_NOTHROW(join(parts));
    std::size_t with = 0;  // a part with regions of both orientations
    while (with < parts.size() &&
           (parts[with].regions[0].regions.empty() || parts[with].regions[1].regions.empty()))
        ++with;
    REQUIRE(with < parts.size());

    std::vector<TilePart> swapped = parts;
    std::swap(swapped[0], swapped[1]);
    CHECK_THROWS_WITH(join(swapped), Catch::Contains("the part of another pass or tile"));
    std::vector<TilePart> short_depths = parts;
    short_depths[with].region_depths[1].peak.pop_back();
    CHECK_THROWS_WITH(join(short_depths), Catch::Contains("its depths do not match its regions"));
    std::vector<TilePart> other_threshold = parts;
    other_threshold[3].thresholds[0] += 1e-9;
    CHECK_THROWS_WITH(join(other_threshold),
                      Catch::Contains("tile 4's part of pass texels does not fit this run: its "
                                      "seed thresholds are not those of tile 1's part"));
    // A region of one tile grown again by another.
    std::vector<TilePart> twice = parts;
    const std::size_t other = (with + 1) % parts.size();
    twice[other].regions[0].regions.push_back(parts[with].regions[0].regions.front());
    twice[other].region_depths[0].seed.push_back(parts[with].region_depths[0].seed.front());
    const std::size_t n = parts[with].regions[0].regions.front().faces.size();
    const RegionDepths& from = parts[with].region_depths[0];
    twice[other].region_depths[0].face.insert(twice[other].region_depths[0].face.end(),
                                              from.face.begin(), from.face.begin() + n);
    twice[other].region_depths[0].peak.insert(twice[other].region_depths[0].peak.end(),
                                              from.peak.begin(), from.peak.begin() + n);
    CHECK_THROWS_WITH(join(twice), Catch::Contains("two texel parts grow a region from vertex"));
    // The same face with another depth.
    twice[other].region_depths[0].face.back() += 1e-9;
    CHECK_THROWS_WITH(join(twice), Catch::Contains("different depths"));
    // The joined texels and their depths must agree.
    JoinedTexels joined = join(parts);
    std::vector<TilePart> rim_parts;
    for (int b = 0; b < run.num_tiles(); ++b) rim_parts.push_back(run.run_tile(b));
    const auto join_rims_of = [&](const std::vector<TilePart>& given) {
        return join_rims(tile, joined, p,
                         [given](int k) { return given[static_cast<std::size_t>(k)]; });
    };
    JoinedRims rims = join_rims_of(rim_parts);
    std::vector<TilePart> extra_flag = rim_parts;
    extra_flag[2].rims.negative_rim.push_back(0);
    CHECK_THROWS_WITH(join_rims_of(extra_flag),
                      Catch::Contains("tile 3's part of pass rims does not fit this run: it has "
                                      "flags of"));
    // From the parts alone, the first part's counts are the run's: another's extra flag, or a
    // part of another tile, is refused the same way.
    const auto join_alone = [&](const std::vector<TilePart>& given) {
        return join_rims_alone(static_cast<int>(given.size()), p,
                               [given](int k) { return given[static_cast<std::size_t>(k)]; });
    };
    CHECK(join_alone(rim_parts).use == rims.use);
    CHECK_THROWS_WITH(join_alone(extra_flag),
                      Catch::Contains("tile 3's part of pass rims does not fit this run: it has "
                                      "flags of"));
    std::vector<TilePart> swapped_rims = rim_parts;
    std::swap(swapped_rims[0], swapped_rims[1]);
    CHECK_THROWS_WITH(join_alone(swapped_rims),
                      Catch::Contains("tile 1's part of pass rims does not fit this run: it is "
                                      "the part of another pass or tile"));
    CHECK_THROWS_AS(join_rims_alone(0, p, [](int) -> TilePart { throw std::logic_error("read"); }),
                    InvalidInput);
    if (!rims.second.orientations.empty()) {
        rims.use[0].push_back(1);
        rims.use[1].push_back(1);
        CHECK_THROWS_WITH(depth_without_rims_part(tile, joined, rims, p),
                          Catch::Contains("do not fit the texels"));
    }
    rims.second.orientations.clear();
    CHECK_THROWS_WITH(depth_without_rims_part(tile, joined, rims, p),
                      Catch::Contains("leave nothing out of a second smoothing"));
    joined.depth[0].push_back(0.0);
    CHECK_THROWS_WITH(rims_part(tile, joined, p), Catch::Contains("depths do not match"));
}
