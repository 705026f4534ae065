// A tile's parts of every pass after the depths made from its tile mesh and the parts of the
// passes before, without the whole mesh (geometry/tile_alone.hpp, the jobs of `--tile-dir
// --pass`): the parts the whole run gives, bit for bit; a texel that outgrows the tile's halo
// sends it to the whole mesh; parts that do not fit are refused, saying why.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
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
#include "pipeline/tile_parts.hpp"
#include "tests/fixtures.hpp"
#include "tests/sparql_test_support.hpp"
#include "tests/tile_test_support.hpp"

using namespace geotex;
using sparql_test::TempFile;
using test::same_bits;
using tile_test::depth_parts;
using tile_test::fast_params;
using tile_test::same_depths;

namespace {

// Each part's depths written sorted to a file, as a depth job writes them beside its part.
std::vector<std::unique_ptr<TempFile>> sorted_files(const std::vector<TilePart>& parts) {
    std::vector<std::unique_ptr<TempFile>> files;
    for (const TilePart& part : parts) {
        std::ostringstream out;
        write_sorted_depths(out, "key", part);
        files.push_back(std::make_unique<TempFile>("tile.sorted", out.str()));
    }
    return files;
}

// The seeds' thresholds of the texel pass after depth pass `of` as a texel job takes them:
// merged from the parts' sorted depths.
std::vector<double> merged_thresholds(const DepthTile& tile, const SegmentationParams& p,
                                      const DepthPassOf& of, const std::vector<TilePart>& parts) {
    const std::vector<std::unique_ptr<TempFile>> files = sorted_files(parts);
    return texel_thresholds_merged(tile, p, of, [&](int k, std::size_t i) {
        return SortedDepthsFile(files[static_cast<std::size_t>(k)]->path(), "key", of.pass, k)
            .values(i);
    });
}

// A part's bytes on disk: two parts with the same bytes are the same part.
std::string write_part_bytes(const TilePart& part) {
    std::ostringstream out;
    write_tile_part(out, "key", part);
    return out.str();
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
    const TilePartSource part_of = [&](int k) { return parts[static_cast<std::size_t>(k)]; };
    const DepthTile first = run.depth_tile(0);
    // The thresholds merged from every tile's sorted depths, written and read back as the jobs
    // do (a job merges them instead of holding every vertex's depth).
    const std::vector<std::unique_ptr<TempFile>> files = sorted_files(parts);
    int opened = 0;
    const SortedDepthSource sorted_of = [&](int k, std::size_t i) {
        ++opened;
        return SortedDepthsFile(files[static_cast<std::size_t>(k)]->path(), "key", TilePass::Depth,
                                k)
            .values(i);
    };
    const std::vector<double> thresholds =
        texel_thresholds_merged(first, p, first_depth_pass(p), sorted_of);
    CHECK(opened == 8);  // each tile's file, each orientation
    // Otsu over the joined maps, the isolated vertex's zero among them, bit for bit.
    REQUIRE(thresholds.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
        std::vector<double> joined(m.positions.size(), 0.0);
        for (const TilePart& part : parts)
            for (std::size_t k = 0; k < part.vertices.size(); ++k)
                joined[part.vertices[k]] = part.depths[i][k];
        CHECK(same_bits(thresholds[i],
                        texel_global_threshold(joined, detail::texel_params(p, first.radius))));
    }
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
        merged_thresholds(run.depth_tile(0), p, first_depth_pass(p), parts);
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

TEST_CASE("a tile job that lets its mesh go while its texels grow in a cut makes the same part",
          "[tiles]") {
    // Regions whole in the first cut (the tile's mesh is let go and never read again), regions
    // that reach a cut's edge (read again for the next cut, or to grow in the tile itself),
    // and the ridge that outgrows every halo.
    struct Case {
        Mesh mesh;
        double radius_rel;
        int tiles;
    };
    std::vector<Case> cases;
    cases.push_back({test::half_engraved_sphere(6), fast_params().radius_rel, 4});
    cases.push_back({test::make_grid(200, 1.0,
                                     [](double x, double) {
                                         return 0.01 * std::exp(-(x - 0.3) * (x - 0.3) /
                                                                (2 * 0.01 * 0.01));
                                     }),
                     0.02, 4});
    int parts_made = 0, never_read = 0, read_again = 0;
    for (const Case& c : cases) {
        SegmentationParams p = fast_params();
        p.radius_rel = c.radius_rel;
        TiledSegmentation run(c.mesh, p, c.tiles);
        const std::vector<TilePart> depth = depth_parts(run);
        const TilePartSource part_of = [&](int k) { return depth[static_cast<std::size_t>(k)]; };
        const std::vector<double> thresholds =
            merged_thresholds(run.depth_tile(0), p, first_depth_pass(p), depth);
        for (int b = 0; b < run.num_tiles(); ++b) {
            const DepthTile tile = run.depth_tile(b);
            const auto depths = depths_in_tile(tile, p, first_depth_pass(p), part_of);
            const std::optional<TilePart> held =
                texel_part_in_tile(tile, depths, thresholds, p, first_depth_pass(p));
            int reads = 0;
            const std::optional<TilePart> let_go =
                texel_part_in_tile(tile, depths, thresholds, p, first_depth_pass(p), [&] {
                    ++reads;
                    return run.depth_tile(b).mesh.mesh;
                });
            REQUIRE(held.has_value() == let_go.has_value());
            if (held) {
                ++parts_made;
                CHECK(write_part_bytes(*held) == write_part_bytes(*let_go));
            }
            (reads == 0 ? never_read : read_again) += 1;
        }
    }
    CHECK(parts_made > 0);
    CHECK(never_read > 0);
    CHECK(read_again > 0);

    // A mesh read again that is not the tile's is refused.
    SegmentationParams p = fast_params();
    p.radius_rel = 0.02;
    TiledSegmentation run(cases[1].mesh, p, 4);
    const std::vector<TilePart> depth = depth_parts(run);
    const TilePartSource part_of = [&](int k) { return depth[static_cast<std::size_t>(k)]; };
    const std::vector<double> thresholds =
        merged_thresholds(run.depth_tile(0), p, first_depth_pass(p), depth);
    int refused = 0;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const DepthTile tile = run.depth_tile(b);
        bool asked = false;
        const auto other_mesh = [&] {
            asked = true;
            Mesh m = run.depth_tile(b).mesh.mesh;
            m.faces.pop_back();
            return m;
        };
        const auto make = [&] {
            return texel_part_in_tile(tile, depths_in_tile(tile, p, first_depth_pass(p), part_of),
                                      thresholds, p, first_depth_pass(p), other_mesh);
        };
        bool threw = false;
        try {
            make();
        } catch (const InvalidInput& e) {
            CHECK(std::string(e.what()).find("mesh read again is not the one read first") !=
                  std::string::npos);
            threw = true;
        }
        CHECK(threw == asked);  // refused exactly when read again
        refused += threw;
    }
    CHECK(refused > 0);
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
    CHECK_THROWS_WITH(depths_in_tile(tile, p, first_depth_pass(p), with(swapped)),
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
    CHECK_THROWS_WITH(merged_thresholds(tile, p, first_depth_pass(p), owned_twice),
                      Catch::Contains("the sorted depths of pass depth give more depths than the "
                                      "mesh has vertices"));
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
    const std::vector<double> thresholds = merged_thresholds(tile, p, first_depth_pass(p), parts);
    CHECK_THROWS_WITH(texel_part_in_tile(tile, {}, thresholds, p, first_depth_pass(p)),
                      Catch::Contains("do not fit its vertices"));
}

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
    const std::vector<double> thresholds = merged_thresholds(first, p, rims_joined.second, second);
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
    CHECK_THROWS_WITH(depths_in_tile(first, p, rims_joined.second,
                                     [&](int k) { return depths[static_cast<std::size_t>(k)]; }),
                      Catch::Contains("part of pass depth-without-rims does not fit"));
}

TEST_CASE("the texel join gives the same texels whatever the order its parts come in", "[tiles]") {
    const Mesh m = test::half_engraved_sphere(6);
    SegmentationParams p = fast_params();
    p.orientation = OrientationMode::Both;
    TiledSegmentation run(m, p, 4);
    const std::vector<TilePart> parts = texel_parts(run, "k");
    const DepthTile first = run.depth_tile(0);
    const TexelParams tp = detail::texel_params(p, first.radius);
    for (std::size_t i = 0; i < 2; ++i) {
        const DetailOrientation o =
            i == 0 ? DetailOrientation::Positive : DetailOrientation::Negative;
        // Faces claimed by two regions, which the join keeps once.
        std::vector<int> claims;
        for (const TilePart& part : parts)
            for (const TexelRegion& r : part.regions[i].regions)
                claims.insert(claims.end(), r.faces.begin(), r.faces.end());
        std::sort(claims.begin(), claims.end());
        REQUIRE(std::unique(claims.begin(), claims.end()) != claims.end());

        detail::TexelRegionJoin forward, backward;
        for (const TilePart& part : parts) forward.add(part.regions[i], part.region_depths[i]);
        for (auto it = parts.rbegin(); it != parts.rend(); ++it)
            backward.add(it->regions[i], it->region_depths[i]);
        std::vector<double> depth_forward, depth_backward;
        const TexelSet a = forward.merge(tp, o, parts[0].thresholds[i], depth_forward);
        const TexelSet b = backward.merge(tp, o, parts[0].thresholds[i], depth_backward);
        REQUIRE(a.texels.size() == b.texels.size());
        CHECK(a.texels.size() >= 5);
        for (std::size_t t = 0; t < a.texels.size(); ++t) {
            CHECK(a.texels[t].faces == b.texels[t].faces);
            CHECK(a.texels[t].seed == b.texels[t].seed);
            CHECK(same_bits(a.texels[t].depth_mean, b.texels[t].depth_mean));
            CHECK(same_bits(a.texels[t].depth_std, b.texels[t].depth_std));
            CHECK(same_bits(depth_forward[t], depth_backward[t]));
        }
        CHECK(a.num_merges == b.num_merges);
    }
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
