// The files beside a tiled run's depth parts (pipeline/sorted_depths.hpp): each tile's depths
// sorted, read back a block at a time as written, with the part's summary for the join, and
// the seeds' thresholds a texel job leaves; another run's, pass's or tile's, or a damaged one,
// refused, naming the file.

#include <algorithm>
#include <catch2/catch.hpp>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "geometry/otsu.hpp"
#include "pipeline/detail/framed_file.hpp"
#include "pipeline/sorted_depths.hpp"
#include "tests/fixtures.hpp"
#include "tests/sparql_test_support.hpp"
#include "tests/tile_test_support.hpp"

using namespace geotex;
using sparql_test::TempFile;
using test::same_bits;
using tile_test::depth_parts;
using tile_test::fast_params;

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
    // The part's summary, which the join of the outputs takes instead of the part: the
    // greatest depths from 0, as the join takes them of a part, and its counts.
    REQUIRE(file.summary().has_value());
    const DepthPartSummary& summary = *file.summary();
    CHECK(summary.tile == 1);
    CHECK(summary.moved == parts[1].moved);
    CHECK(summary.interpolated == parts[1].interpolated);
    CHECK(summary.samples == parts[1].samples);
    CHECK(summary.samples + summary.interpolated > 0);
    REQUIRE(summary.greatest.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
        double most = 0;
        for (double d : parts[1].depths[i]) most = std::max(most, d);
        CHECK(same_bits(summary.greatest[i], most));
    }
    // A file made before the summary was kept has none, and reads as before.
    {
        std::istringstream in(bytes);
        detail::Cbor header = detail::read_framed_header(in, "geotex sorted depths\n",
                                                         "sorted depths file", 1, "key");
        for (const char* name : {"moved", "interpolated", "samples"}) header.erase(name);
        std::ostringstream old;
        detail::write_framed_header(old, "geotex sorted depths\n", header);
        old << in.rdbuf();
        const TempFile before("tile-2.sorted", old.str());
        const SortedDepthsFile without(before.path(), "key", TilePass::Depth, 1);
        CHECK_FALSE(without.summary().has_value());
        CHECK(without.greatest() == file.greatest());
        header["moved"] = {-1, 0};
        header["interpolated"] = 0;
        header["samples"] = 0;
        std::ostringstream negative;
        detail::write_framed_header(negative, "geotex sorted depths\n", header);
        std::istringstream again(bytes);
        detail::read_framed_header(again, "geotex sorted depths\n", "sorted depths file", 1, "key");
        negative << again.rdbuf();
        CHECK_THAT(refusal(negative.str(), "key", TilePass::Depth, 1),
                   Catch::Contains("its part's counts are wrong"));
    }
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
