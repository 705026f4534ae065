// The scale series of issue 20 (geometry/scale_series.hpp, docs/scales.md): the series of
// radii, the matching of texels across scales, the rule that finds plateaus, and a run over
// the paper's sphere whose shapes are known.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include "common/errors.hpp"
#include "geometry/scale_series.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

TEST_CASE("scale_series_radii: a geometric series from the smallest to the largest scale",
          "[geometry][scales]") {
    ScaleSeriesParams p;
    p.min_rel = 0.01;
    p.max_rel = 0.16;
    p.steps = 5;
    const auto r = scale_series_radii(p);
    REQUIRE(r.size() == 5);
    const double expected[] = {0.01, 0.02, 0.04, 0.08, 0.16};
    for (int k = 0; k < 5; ++k) CHECK(r[k] == Approx(expected[k]).epsilon(1e-12));
    CHECK(r.back() == 0.16);

    p.steps = 1;
    CHECK_THROWS_AS(scale_series_radii(p), InvalidInput);
    p.steps = 4;
    p.min_rel = 0.2;
    CHECK_THROWS_AS(scale_series_radii(p), InvalidInput);
    p.min_rel = 0.01;
    p.max_rel = 1.0;
    CHECK_THROWS_AS(scale_series_radii(p), InvalidInput);
}

TEST_CASE(
    "persisting_texels: a texel persists when a texel of the other scale covers nearly "
    "the same faces",
    "[geometry][scales]") {
    // Ten faces. At scale a: texel 0 on faces 0-3, texel 1 on faces 5-7, texel 2 on face 9.
    // At scale b: texel 0 on faces 0-4 (shares 4 of 5 with a's texel 0: IoU 0.8), texel 1 on
    // faces 7-9 (shares 1 of 5 with a's texel 1: IoU 0.2; all of a's texel 2: IoU 1/3).
    const std::vector<int> a = {0, 0, 0, 0, -1, 1, 1, 1, -1, 2};
    const std::vector<int> b = {0, 0, 0, 0, 0, -1, -1, 1, 1, 1};
    CHECK(persisting_texels(a, 3, b, 2, 0.5) == std::vector<bool>{true, false, false});
    CHECK(persisting_texels(b, 2, a, 3, 0.5) == std::vector<bool>{true, false});
    // A stricter match refuses the 0.8 overlap.
    CHECK(persisting_texels(a, 3, b, 2, 0.85) == std::vector<bool>{false, false, false});
    // No texels at all: nothing persists, and nothing breaks.
    const std::vector<int> none(10, -1);
    CHECK(persisting_texels(none, 0, b, 2, 0.5).empty());
    CHECK(persisting_texels(b, 2, none, 0, 0.5) == std::vector<bool>{false, false});
    CHECK_THROWS_AS(persisting_texels(a, 3, std::vector<int>(9, -1), 0, 0.5), InvalidInput);
    CHECK_THROWS_AS(persisting_texels(a, 2, b, 2, 0.5), InvalidInput);  // a's texel 2 >= 2

    // The counts both rules use: texel sizes and the faces each meeting pair shares.
    const TexelOverlaps o = texel_overlaps(a, 3, b, 2);
    CHECK(o.size_a == std::vector<long>{4, 3, 1});
    CHECK(o.size_b == std::vector<long>{5, 3});
    std::vector<std::array<long, 3>> pairs;
    for (const auto& p : o.pairs) pairs.push_back({p.a, p.b, p.shared});
    std::sort(pairs.begin(), pairs.end());
    CHECK(pairs == std::vector<std::array<long, 3>>{{0, 0, 4}, {1, 1, 1}, {2, 1, 1}});
}

namespace {

ScaleStep step(int texels, int previous, int next, bool skipped = false) {
    ScaleStep s;
    s.texels = texels;
    s.persist_previous = previous;
    s.persist_next = next;
    s.skipped = skipped;
    return s;
}

}  // namespace

TEST_CASE(
    "choose_scales: plateaus are runs of stable scales; each recommends its scale with "
    "the most persistent texels",
    "[geometry][scales]") {
    // A made-up series, worked out by hand with stable_fraction 0.8:
    //   0 skipped (too fine for the sampling)
    //   1: 30 texels, 5 match the next               -> persistent 5 (end: next only), 0.17
    //   2: 20 texels, 6 previous, 16 next            -> 6, 0.30
    //   3: 16 texels, 16 previous, 15 next           -> 15, 0.94 stable
    //   4: 16 texels, 15 previous, 16 next           -> 15, 0.94 stable
    //   5: 16 texels, 16 previous, 10 next           -> 10, 0.63
    //   6: 11 texels, 10 previous, 11 next           -> 10, 0.91 stable
    //   7: 11 texels, 11 previous (the end)          -> 11, 1.00 stable
    ScaleSeries series;
    series.steps = {step(0, 0, 0, true), step(30, 0, 5),   step(20, 6, 16),  step(16, 16, 15),
                    step(16, 15, 16),    step(16, 16, 10), step(11, 10, 11), step(11, 11, 0)};
    ScaleSeriesParams p;
    p.stable_fraction = 0.8;
    choose_scales(series, p);
    const int persistent[] = {0, 5, 6, 15, 15, 10, 10, 11};
    const bool stable[] = {false, false, false, true, true, false, true, true};
    for (int k = 0; k < 8; ++k) {
        INFO("step " << k);
        CHECK(series.steps[k].persistent == persistent[k]);
        CHECK(series.steps[k].stable == stable[k]);
    }
    CHECK(series.steps[3].stability == Approx(15.0 / 16));
    REQUIRE(series.plateaus.size() == 2);
    CHECK(series.plateaus[0].first == 3);
    CHECK(series.plateaus[0].last == 4);
    CHECK(series.plateaus[0].recommended == 3);  // a tie: the finer scale
    CHECK(series.plateaus[1].first == 6);
    CHECK(series.plateaus[1].last == 7);
    CHECK(series.plateaus[1].recommended == 7);
    CHECK(series.best == 3);  // 15 persistent texels against 11

    // Within a plateau, the scales with nearly (95%) the most persistent texels: 32 of the
    // plateau's most, 33, is near enough; it and the next have 2 texels that do not persist
    // each, and the finer is taken.
    ScaleSeries near;
    near.steps = {step(200, 0, 30), step(34, 32, 34), step(35, 34, 33), step(38, 33, 33),
                  step(43, 29, 0)};
    choose_scales(near, p);
    CHECK(near.steps[1].persistent == 32);
    CHECK(near.steps[2].persistent == 33);
    REQUIRE(near.plateaus.size() == 1);
    CHECK(near.plateaus[0].first == 1);
    CHECK(near.plateaus[0].last == 3);
    CHECK(near.plateaus[0].recommended == 1);
    CHECK(near.best == 1);
    p.near_most = 1.0;  // only the most will do
    choose_scales(near, p);
    CHECK(near.best == 2);
    p.near_most = 0.95;

    // Of the near-most scales, the one with the fewest texels that do not persist: here (the
    // numbers of sphere-1 with both orientations) the finer 95 texels hold 88 persistent and
    // 7 split pieces, the next 92 texels only 4.
    ScaleSeries split;
    split.steps = {step(97, 0, 83), step(95, 88, 88), step(92, 88, 88), step(100, 88, 88),
                   step(96, 88, 0)};
    choose_scales(split, p);
    REQUIRE(split.plateaus.size() == 1);
    CHECK(split.plateaus[0].first == 0);
    CHECK(split.plateaus[0].last == 4);
    CHECK(split.steps[0].persistent == 83);  // below 95% of 88: not a candidate
    CHECK(split.plateaus[0].recommended == 2);
    CHECK(split.best == 2);

    // One stable scale alone is no plateau: here the last, compared with one neighbour only.
    ScaleSeries lone;
    lone.steps = {step(20, 0, 10), step(16, 10, 14), step(14, 14, 0)};
    choose_scales(lone, p);
    CHECK(lone.steps[2].stable);
    CHECK(lone.plateaus.empty());
    CHECK(lone.best == -1);

    // No texel at any scale: no plateau, no best.
    ScaleSeries empty;
    empty.steps = {step(0, 0, 0), step(0, 0, 0), step(0, 0, 0)};
    choose_scales(empty, p);
    CHECK(empty.plateaus.empty());
    CHECK(empty.best == -1);
}

TEST_CASE("run_scale_series: a perfect sphere has no stable scale", "[geometry][scales]") {
    ScaleSeriesParams p;
    p.min_rel = 0.04;
    p.max_rel = 0.16;
    p.steps = 3;
    const ScaleSeries series = run_scale_series(test::make_sphere(1.0, 5), {}, p);
    REQUIRE(series.steps.size() == 3);
    for (const ScaleStep& s : series.steps) CHECK(s.texels == 0);
    CHECK(series.best == -1);
    CHECK(series.plateaus.empty());
}

TEST_CASE("choose_scale: the best stable scale, else the one with the most persistent texels",
          "[geometry][scales]") {
    ScaleSeriesParams p;
    ScaleSeries stable;
    // Persistent texels 13, 15 and 14 of 16: all stable, one plateau, the middle one best.
    stable.steps = {step(0, 0, 0, true), step(16, 0, 13), step(16, 15, 16), step(16, 14, 0)};
    choose_scales(stable, p);
    REQUIRE(stable.best == 2);
    const ScaleChoice a = choose_scale(stable, p);
    CHECK(a.chosen == 2);
    CHECK(a.stable);
    CHECK(a.series.steps.size() == 4);

    // Nothing stable: 30 texels of which 5 persist, then 20 of which 6 do, then 40 of which
    // 3: the second, with the most persistent texels, although it has fewer texels.
    ScaleSeries unstable;
    unstable.steps = {step(30, 0, 5), step(20, 6, 8), step(40, 3, 0)};
    choose_scales(unstable, p);
    REQUIRE(unstable.best == -1);
    const ScaleChoice b = choose_scale(unstable, p);
    CHECK(b.chosen == 1);
    CHECK_FALSE(b.stable);

    // No detail anywhere: the finest computed scale (all find nothing).
    ScaleSeries none;
    none.steps = {step(0, 0, 0, true), step(0, 0, 0), step(0, 0, 0)};
    choose_scales(none, p);
    CHECK(choose_scale(none, p).chosen == 1);

    // Every scale skipped: nothing to choose from.
    ScaleSeries skipped;
    skipped.steps = {step(0, 0, 0, true), step(0, 0, 0, true)};
    choose_scales(skipped, p);
    CHECK_THROWS_AS(choose_scale(skipped, p), InvalidInput);
}

namespace {

// Everything a series or a report reads of a segmentation is the same, bit for bit.
void require_same(const Segmentation& a, const Segmentation& b) {
    CHECK(a.radius == b.radius);
    REQUIRE(a.texels.size() == b.texels.size());
    CHECK(a.face_texel == b.face_texel);
    CHECK(a.num_textures == b.num_textures);
    CHECK(a.face_texture == b.face_texture);
    // Bit for bit, NaN included (a feature may be undefined for a texel).
    REQUIRE(a.features.values.size() == b.features.values.size());
    CHECK(std::memcmp(a.features.values.data(), b.features.values.data(),
                      sizeof(double) * static_cast<std::size_t>(a.features.values.size())) == 0);
    CHECK(a.metrics.face_area == b.metrics.face_area);
    CHECK(a.metrics.largest_side == b.metrics.largest_side);
    CHECK(a.topology.vertex_neighbours == b.topology.vertex_neighbours);
    CHECK(a.diagnostics.size() == b.diagnostics.size());
}

}  // namespace

TEST_CASE("SegmentationContext: runs at several scales give run_segmentation's results",
          "[geometry][scales][segmentation]") {
    const Mesh mesh = test::half_engraved_sphere(5);
    SegmentationParams p;
    p.orientation = OrientationMode::Both;
    const SegmentationContext context(mesh);
    for (double scale : {0.03, 0.06}) {
        p.radius_rel = scale;
        const Segmentation shared = context.run(p);
        REQUIRE(!shared.texels.empty());
        require_same(shared, run_segmentation(mesh, p));
    }
    // A mesh far from unit size is run in the unit frame and its results brought back.
    Mesh huge = mesh;
    for (auto& x : huge.positions) x *= std::ldexp(1.0, 40);
    p.radius_rel = 0.04;
    require_same(SegmentationContext(huge).run(p), run_segmentation(huge, p));
    // Bad parameters are refused by each run, as by run_segmentation.
    p.min_faces = 0;
    CHECK_THROWS_AS(context.run(p), InvalidInput);
    CHECK_THROWS_AS(SegmentationContext(Mesh{}), InvalidInput);
}

TEST_CASE("run_scale_series: each scale counts the texels and textures of its own segmentation",
          "[geometry][scales]") {
    const Mesh mesh = test::half_engraved_sphere(5);
    SegmentationParams base;
    base.orientation = OrientationMode::Both;
    ScaleSeriesParams p;
    p.min_rel = 0.07;  // at level 5, 3 mean edge lengths are 5.7% of the largest side
    p.max_rel = 0.16;
    p.steps = 4;
    const ScaleSeries series = run_scale_series(mesh, base, p);
    std::vector<int> previous;  // the face labelling of the previous scale
    for (std::size_t k = 0; k < series.steps.size(); ++k) {
        const ScaleStep& s = series.steps[k];
        REQUIRE_FALSE(s.skipped);
        SegmentationParams at = base;
        at.radius_rel = s.radius_rel;
        const Segmentation seg = run_segmentation(mesh, at);
        CHECK(s.texels == static_cast<int>(seg.texels.size()));
        CHECK(s.textures == seg.num_textures);
        if (k > 0) {
            const auto back = persisting_texels(seg.face_texel, s.texels, previous,
                                                series.steps[k - 1].texels, p.match_iou);
            CHECK(s.persist_previous == std::count(back.begin(), back.end(), true));
        }
        previous = seg.face_texel;
    }
    // Parameters out of range are refused before any scale is segmented.
    base.min_faces = 0;
    CHECK_THROWS_AS(run_scale_series(mesh, base, p), InvalidInput);
}
