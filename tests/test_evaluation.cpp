#include <catch2/catch.hpp>
#include <cmath>

#include "common/errors.hpp"
#include "geometry/evaluation.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {
std::vector<int> columns(const Mesh& m, int n, int lo, int hi) {
    // Faces of grid cells whose column index is in [lo, hi).
    std::vector<int> out;
    for (int f = 0; f < m.num_faces(); ++f) {
        const int cell = f / 2, i = cell % n;
        if (i >= lo && i < hi) out.push_back(f);
    }
    return out;
}
}  // namespace

TEST_CASE("surfacic_hausdorff: identical, shifted and empty sets", "[geometry][evaluation]") {
    const int n = 10;
    const Mesh m = test::make_grid(n, 1.0);  // cells of 0.1
    const auto a = columns(m, n, 2, 4);
    CHECK(surfacic_hausdorff(m, a, a) == 0);
    // Columns 2-3 against columns 5-6: the far column of each band is 0.3 from the near
    // column of the other (plus at most a third of a cell sideways: sqrt(0.09 + 0.0011)).
    const auto b = columns(m, n, 5, 7);
    const double d = surfacic_hausdorff(m, a, b);
    CHECK(d == Approx(surfacic_hausdorff(m, b, a)));
    CHECK(d > 0.2);
    CHECK(d < 0.31);
    CHECK(surfacic_hausdorff(m, {}, {}) == 0);
    CHECK(std::isinf(surfacic_hausdorff(m, a, {})));
    REQUIRE_THROWS_AS(surfacic_hausdorff(m, {-1}, a), InvalidInput);
}

TEST_CASE("evaluate_segmentation: matching, Hausdorff and delta_t on a grid",
          "[geometry][evaluation]") {
    const int n = 20;
    const Mesh m = test::make_grid(n, 1.0);
    GroundTruth gt;
    gt.face_shape.assign(m.num_faces(), -1);
    gt.shape_kind = {0, 0, 1};
    gt.shape_family = {0, 0, 0};
    for (int f : columns(m, n, 1, 3)) gt.face_shape[f] = 0;
    for (int f : columns(m, n, 6, 8)) gt.face_shape[f] = 1;
    for (int f : columns(m, n, 12, 15)) gt.face_shape[f] = 2;
    // Texels: shape 0 exactly, shape 1 split in two, shape 2 missed, one spurious band.
    std::vector<int> texel(m.num_faces(), -1), texture(m.num_faces(), -1);
    for (int f : columns(m, n, 1, 3)) texel[f] = 0, texture[f] = 0;
    for (int f : columns(m, n, 6, 7)) texel[f] = 1, texture[f] = 0;
    for (int f : columns(m, n, 7, 8)) texel[f] = 2, texture[f] = 0;
    for (int f : columns(m, n, 17, 18)) texel[f] = 3, texture[f] = 1;
    const SegmentationScore s = evaluate_segmentation(m, texel, texture, gt);
    CHECK(s.num_shapes == 3);
    CHECK(s.num_texels == 4);
    CHECK(s.num_matched == 1);
    CHECK(s.num_split == 1);
    CHECK(s.num_missed == 1);
    CHECK(s.num_spurious == 1);
    // Textures of the covering texels (0, 0, 0) against kinds (0, 0, 0): identical partitions.
    CHECK(s.ari_kind == Approx(1.0));
    // Matched-only Hausdorff: the missed shape (columns 12-14) is 0.2 - 0.25 away from the
    // nearest texel face; both are > 0 and finite.
    CHECK(s.hausdorff > 0);
    CHECK(std::isfinite(s.hausdorff_matched));
    // delta_t: grid cells of 1/20 split in two right triangles; adjacent barycentres are at
    // sqrt(2)/3 * h (across the diagonal) or sqrt(5)/3 * h ... across the cell edges; the
    // mean lies between h/3*sqrt(2) and h*sqrt(5)/3 (h = 0.05, largest side 1).
    const double h = 0.05;
    CHECK(s.delta_t > h * std::sqrt(2.0) / 3);
    CHECK(s.delta_t < h * std::sqrt(5.0) / 3 + 1e-12);
    REQUIRE_THROWS_AS(evaluate_segmentation(m, {0}, texture, gt), InvalidInput);
}
