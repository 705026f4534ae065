// Several levels at once (geometry/scale_levels.hpp, docs/scales.md "Several levels"): which
// coarse texel a fine one lies on, which scales become levels, and that each level is the
// segmentation at its scale. The paper's two-level sphere, with its ground truth, is
// tests/levels_test.sh.

#include <catch2/catch.hpp>

#include "common/errors.hpp"
#include "geometry/scale_levels.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

TEST_CASE("covering_texels: a fine texel lies on the coarse texel holding more than half of it",
          "[geometry][scales]") {
    // Twelve faces. Fine texel 0 on faces 0-2, two of them in coarse texel 1: 2/3 > 1/2.
    // Fine texel 1 on faces 4-7, half in coarse 0 and half in coarse 1: on neither.
    // Fine texel 2 on face 9, outside every coarse texel. Fine texel 3 on faces 10-11, both in
    // coarse texel 0, which is much larger: the cover is of the fine texel, not the union.
    const std::vector<int> fine = {0, 0, 0, -1, 1, 1, 1, 1, -1, 2, 3, 3};
    const std::vector<int> coarse = {1, 1, -1, 1, 0, 0, 1, 1, 0, -1, 0, 0};
    CHECK(covering_texels(fine, 4, coarse) == std::vector<int>{1, -1, -1, 0});
    // A stricter cover drops texel 0 (2/3) but keeps texel 3 (2/2).
    CHECK(covering_texels(fine, 4, coarse, 0.7) == std::vector<int>{-1, -1, -1, 0});
    // A fine texel without faces lies on nothing.
    CHECK(covering_texels(fine, 5, coarse) == std::vector<int>{1, -1, -1, 0, -1});

    CHECK_THROWS_AS(covering_texels(fine, 4, std::vector<int>(11, -1)), InvalidInput);
    CHECK_THROWS_AS(covering_texels(fine, 3, coarse), InvalidInput);  // id 3 >= count
    CHECK_THROWS_AS(covering_texels(fine, 4, coarse, 0.4), InvalidInput);
}

TEST_CASE("level_steps: each plateau's recommended scale, fine to coarse, with the chosen one",
          "[geometry][scales]") {
    ScaleChoice choice;
    choice.series.steps.resize(12);
    choice.series.plateaus = {{2, 4, 2}, {7, 11, 8}};
    choice.chosen = 8;
    CHECK(level_steps(choice) == std::vector<int>{2, 8});
    // No plateau: the fallback scale alone.
    choice.series.plateaus.clear();
    choice.chosen = 5;
    CHECK(level_steps(choice) == std::vector<int>{5});
}

TEST_CASE("segment_levels: each level is the segmentation at its scale, linked to the next",
          "[geometry][scales]") {
    // A wavy grid: broad swells carrying fine ripples, so that both scales find texels.
    const Mesh mesh = test::make_grid(80, 1.0, [](double x, double y) {
        return 0.04 * std::cos(6 * x) * std::cos(6 * y) +
               0.004 * std::cos(40 * x) * std::cos(40 * y);
    });
    ScaleChoice choice;
    choice.series.steps.resize(3);
    choice.series.steps[0].radius_rel = 0.03;
    choice.series.steps[1].radius_rel = 0.06;
    choice.series.steps[2].radius_rel = 0.15;
    choice.series.plateaus = {{0, 0, 0}, {2, 2, 2}};
    choice.chosen = 2;
    SegmentationParams base;
    base.radius_rel = 0.15;
    const Segmentation main = run_segmentation(mesh, base);
    const std::vector<DetailLevel> levels = segment_levels(mesh, base, choice, main);
    REQUIRE(levels.size() == 2);
    CHECK(levels[0].step == 0);
    CHECK_FALSE(levels[0].main);
    CHECK(levels[1].main);
    CHECK(levels[1].segmentation.texels.empty());  // the caller holds the main one

    SegmentationParams fine_params = base;
    fine_params.radius_rel = 0.03;
    const Segmentation fine = run_segmentation(mesh, fine_params);
    REQUIRE_FALSE(fine.texels.empty());
    REQUIRE_FALSE(main.texels.empty());
    CHECK(level_segmentation(levels, 0, main).face_texel == fine.face_texel);
    CHECK(&level_segmentation(levels, 1, main) == &main);
    CHECK(levels[0].part_of ==
          covering_texels(fine.face_texel, static_cast<int>(fine.texels.size()), main.face_texel));
    CHECK(levels[1].part_of == std::vector<int>(main.texels.size(), -1));  // the coarsest
    INFO("fine texels " << fine.texels.size() << ", coarse " << main.texels.size());
    int linked = 0;
    for (int c : levels[0].part_of) linked += c >= 0;
    CHECK(linked > 0);
}
