// The unit frame: meshes in any unit from 1e-300 to 1e300 give the same texels (issue 17,
// finding 9), and sizes no double holds are refused.

#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>

#include "common/errors.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/synth.hpp"
#include "geometry/unit_frame.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;
using geotex::test::scaled;

namespace {

Mesh sphere(int level) {
    SynthParams sp;
    sp.level = level;
    return make_synthetic_sphere(sp).mesh;
}

SegmentationParams at_scale(double radius_rel, OrientationMode orientation) {
    SegmentationParams p;
    p.radius_rel = radius_rel;
    p.orientation = orientation;
    return p;
}

}  // namespace

TEST_CASE("make_unit_frame: the largest side and its power of two", "[geometry][unit_frame]") {
    const std::vector<Eigen::Vector3d> box = {{-1, 0, 0}, {2, 0.5, 0}, {0, 0, 1}};
    const UnitFrame f = make_unit_frame(box);
    CHECK(f.largest_side == 3);  // x spans 3, y 0.5, z 1
    CHECK(f.exponent == 1);      // 3 / 2^1 is in [1, 2)
    // A side a double difference overflows (1.7e308 - -1.7e308) is seen, not taken for 0
    const std::vector<Eigen::Vector3d> huge = {{-1.7e308, 0, 0}, {1.7e308, 0, 0}};
    CHECK_THROWS_WITH(make_unit_frame(huge), Catch::Contains("beyond the largest double"));
    // The largest side that a double holds is accepted
    const std::vector<Eigen::Vector3d> widest = {{-DBL_MAX / 2, 0, 0}, {DBL_MAX / 2, 0, 0}};
    CHECK(make_unit_frame(widest).exponent == 1023);
    // Subnormal sizes: 1/side, the unit scale of the outputs, would be infinite
    const std::vector<Eigen::Vector3d> tiny = {{0, 0, 0}, {1e-310, 0, 0}};
    CHECK_THROWS_WITH(make_unit_frame(tiny), Catch::Contains("below the smallest normal double"));
    const std::vector<Eigen::Vector3d> smallest = {{0, 0, 0}, {DBL_MIN, 0, 0}};
    CHECK(make_unit_frame(smallest).exponent == -1022);
    const std::vector<Eigen::Vector3d> point = {{1, 2, 3}, {1, 2, 3}};
    CHECK_THROWS_WITH(make_unit_frame(point), Catch::Contains("all vertices coincide"));
    CHECK_THROWS_AS(make_unit_frame({}), InvalidInput);
}

TEST_CASE("run_segmentation: the same texels in any unit from 1e-300 to 1e300",
          "[geometry][segmentation][unit_frame]") {
    const Mesh mesh = sphere(5);
    const SegmentationParams p = at_scale(0.05, OrientationMode::Positive);
    const Segmentation one = run_segmentation(mesh, p);
    REQUIRE(one.texels.size() > 10);  // else the comparisons below prove nothing
    for (double k : {1e-300, 1e-100, 1e-30, 1e30, 1e100, 1e300}) {
        INFO("scale " << k);
        const Segmentation s = run_segmentation(scaled(mesh, k), p);
        CHECK(s.face_texel == one.face_texel);
        CHECK(s.face_texture == one.face_texture);
        CHECK(s.num_textures == one.num_textures);
        // Lengths come back in the mesh's unit (the scaling itself rounds: a few ulps)
        CHECK(s.radius == Approx(one.radius * k).epsilon(1e-12));
        CHECK(s.metrics.largest_side == Approx(one.metrics.largest_side * k).epsilon(1e-12));
        // Features are computed on the unit-side mesh: the same up to the rounding of the
        // input coordinates, amplified by the quadric fits (1e-9 relative is far below any
        // dictionary bound's precision).
        REQUIRE(s.features.values.rows() == one.features.values.rows());
        CHECK((s.features.values - one.features.values).cwiseAbs().maxCoeff() <=
              1e-9 * (1 + one.features.values.cwiseAbs().maxCoeff()));
    }
}

TEST_CASE("run_segmentation: a power-of-two unit gives exactly scaled results",
          "[geometry][segmentation][unit_frame]") {
    // Multiplying by 2^200 changes no digit of any coordinate, and the unit frame divides it
    // out exactly: every result is the unscaled one times the same power, bit for bit.
    const Mesh mesh = sphere(4);
    const SegmentationParams p = at_scale(0.08, OrientationMode::Both);
    const Segmentation one = run_segmentation(mesh, p);
    const double k = std::ldexp(1.0, 200);
    const Segmentation s = run_segmentation(scaled(mesh, k), p);
    CHECK(s.face_texel == one.face_texel);
    CHECK(s.face_texture == one.face_texture);
    CHECK(s.radius == one.radius * k);
    CHECK(s.features.values == one.features.values);
    REQUIRE(s.positive_depth);
    for (std::size_t v = 0; v < s.positive_depth->vertex_depth.size(); ++v)
        REQUIRE(s.positive_depth->vertex_depth[v] == one.positive_depth->vertex_depth[v] * k);
    // --radius in mesh units is read in the mesh's unit too
    SegmentationParams by_radius = p;
    by_radius.radius = one.radius * k;
    CHECK(run_segmentation(scaled(mesh, k), by_radius).face_texel == one.face_texel);
}
