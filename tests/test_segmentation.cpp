#include <tbb/global_control.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <functional>
#include <limits>
#include <map>
#include <set>

#include "common/errors.hpp"
#include "geometry/evaluation.hpp"
#include "geometry/icosphere.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/synth.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

GroundTruth truth_of(const SyntheticMesh& s) {
    GroundTruth gt;
    gt.face_shape = s.face_shape;
    for (const auto& shape : s.shapes) {
        gt.shape_kind.push_back(static_cast<int>(shape.kind));
        gt.shape_family.push_back(shape.kind == ShapeKind::SmallDisc
                                      ? static_cast<int>(ShapeKind::BigDisc)
                                      : static_cast<int>(shape.kind));
    }
    return gt;
}

}  // namespace

TEST_CASE("run_segmentation: synthetic sphere-1 end to end", "[geometry][segmentation][slow]") {
    SynthParams sp;
    sp.level = 7;  // the paper's 327,680 faces (about 2 s in the Release build of the tests)
    const SyntheticMesh synth = make_synthetic_sphere(sp);
    SegmentationParams p;
    p.radius_rel = 0.04;
    const Segmentation seg = run_segmentation(synth.mesh, p);
    const SegmentationScore s =
        evaluate_segmentation(synth.mesh, seg.face_texel, seg.face_texture, truth_of(synth));
    INFO("matched " << s.num_matched << " missed " << s.num_missed << " split " << s.num_split
                    << " spurious " << s.num_spurious << " textures " << seg.num_textures
                    << " ARI kind " << s.ari_kind << " family " << s.ari_family << " Hausdorff "
                    << s.hausdorff << " delta_t " << s.delta_t);
    // Every shape becomes exactly one texel, no spurious texel.
    CHECK(s.num_shapes == 88);
    CHECK(s.num_matched == 88);
    CHECK(s.num_missed == 0);
    CHECK(s.num_split == 0);
    CHECK(s.num_spurious == 0);
    // Boundaries within two face spacings of the ground truth (paper: about delta_t).
    CHECK(s.hausdorff <= 2 * s.delta_t);
    // Textures separate the kinds (the paper's Fig. 12: big discs, small discs, squares,
    // rectangles)...
    CHECK(s.ari_kind >= 0.9);
    // ...and no texture mixes discs, squares and rectangles.
    std::vector<std::set<int>> families(seg.num_textures);
    const GroundTruth gt = truth_of(synth);
    for (std::size_t i = 0; i < seg.texels.size(); ++i) {
        std::map<int, int> votes;  // shape -> faces of the texel on it
        for (int f : seg.texels[i].faces)
            if (synth.face_shape[f] >= 0) ++votes[synth.face_shape[f]];
        REQUIRE_FALSE(votes.empty());
        const auto best =
            std::max_element(votes.begin(), votes.end(),
                             [](const auto& a, const auto& b) { return a.second < b.second; });
        families[seg.texel_texture[i]].insert(gt.shape_family[best->first]);
    }
    for (const auto& f : families) CHECK(f.size() == 1);
    // Invariants: labels in range, each face in at most one texel (face_texel is a function).
    for (std::size_t i = 0; i < seg.texels.size(); ++i) {
        CHECK(seg.texel_texture[i] >= 0);
        CHECK(seg.texel_texture[i] < seg.num_textures);
        for (int f : seg.texels[i].faces) CHECK(seg.face_texel[f] == static_cast<int>(i));
    }
}

TEST_CASE("run_segmentation: identical results for 1 and 2 threads", "[geometry][segmentation]") {
    SynthParams sp;
    sp.level = 5;
    sp.noise_percent = 0.1;
    const SyntheticMesh synth = make_synthetic_sphere(sp);
    SegmentationParams p;
    p.orientation = OrientationMode::Both;
    Segmentation one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = run_segmentation(synth.mesh, p);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = run_segmentation(synth.mesh, p);
    }
    CHECK(one.face_texel == two.face_texel);
    CHECK(one.face_texture == two.face_texture);
    CHECK(one.positive_depth->vertex_depth == two.positive_depth->vertex_depth);
    CHECK(one.negative_depth->vertex_depth == two.negative_depth->vertex_depth);
    CHECK(one.features.values == two.features.values);
}

TEST_CASE("run_segmentation: engraved shapes found with the negative orientation",
          "[geometry][segmentation][slow]") {
    SynthParams sp;
    sp.level = 6;
    sp.engraved_fraction = 1.0;
    const SyntheticMesh synth = make_synthetic_sphere(sp);
    SegmentationParams p;
    p.orientation = OrientationMode::Negative;
    const Segmentation seg = run_segmentation(synth.mesh, p);
    const SegmentationScore s =
        evaluate_segmentation(synth.mesh, seg.face_texel, seg.face_texture, truth_of(synth));
    CHECK(s.num_matched == 88);
    CHECK(s.num_spurious == 0);
    // Positive details of the engraved sphere lie outside the engravings: the disc mean is
    // pulled down by a pit, so the rim around it stands out at this scale (a property of
    // the paper's eq. 1, recorded in the issue notes); the pit floors never do.
    p.orientation = OrientationMode::Positive;
    const Segmentation pos = run_segmentation(synth.mesh, p);
    const DepthMap& d = *pos.positive_depth;
    for (int v = 0; v < synth.mesh.num_vertices(); ++v)
        if (synth.vertex_grey[v] >= 1.0) CHECK(d.vertex_depth[v] == 0);
}

TEST_CASE("run_segmentation: a perfect sphere has nothing salient", "[geometry][segmentation]") {
    const Segmentation seg = run_segmentation(test::make_sphere(1.0, 5));
    CHECK(seg.texels.empty());
    CHECK(seg.num_textures == 0);
    for (int t : seg.face_texel) CHECK(t == -1);
}

TEST_CASE("run_segmentation: open mesh and two components", "[geometry][segmentation]") {
    // An open square sheet with two bumps, and beside it a closed sphere with none: the
    // sheet's border makes no texel, the bumps do, and the sphere stays clean.
    auto bump = [](double x, double y, double cx, double cy) {
        const double d = std::hypot(x - cx, y - cy) - 0.05;
        return 0.02 * std::max(0.0, std::min(1.0, 0.5 - d / 0.01));
    };
    const Mesh sheet = test::make_grid(120, 1.0, [&](double x, double y) {
        return bump(x, y, -0.2, 0.1) + bump(x, y, 0.25, -0.15);
    });
    const Mesh sphere = test::make_sphere(0.3, 5, Eigen::Vector3d(1.2, 0, 0));
    const Mesh both = test::combined(sheet, sphere);
    SegmentationParams p;
    p.radius = 0.08;
    const Segmentation seg = run_segmentation(both, p);
    REQUIRE(seg.texels.size() == 2);
    for (const auto& t : seg.texels)
        for (int f : t.faces) {
            CHECK(f < sheet.num_faces());  // on the sheet
            double z = 0;
            for (int v : both.faces[f]) z = std::max(z, both.positions[v].z());
            CHECK(z > 0);  // on a bump, not on the border
        }
}

TEST_CASE("resolve_radius: scale and radius preconditions", "[geometry][segmentation]") {
    SegmentationParams p;
    CHECK(resolve_radius(p, 2.0) == Approx(0.08));
    p.radius = 0.5;
    CHECK(resolve_radius(p, 2.0) == 0.5);
    p.radius = -1;
    REQUIRE_THROWS_AS(resolve_radius(p, 2.0), InvalidInput);
    p.radius = 0;
    for (double bad : {0.0, 1.0, -0.1, 2.0}) {
        p.radius_rel = bad;
        REQUIRE_THROWS_AS(resolve_radius(p, 2.0), InvalidInput);
    }
}

TEST_CASE("name tables: every enumerator has one name, and each name parses back to it",
          "[geometry][segmentation]") {
    // The tables must cover their enums: a missing entry would print a null name.
    for (OrientationMode m :
         {OrientationMode::Positive, OrientationMode::Negative, OrientationMode::Both}) {
        REQUIRE(name_of(m) != nullptr);
        CHECK(parse_orientation_mode(name_of(m)) == m);
    }
    for (SmoothingMethod m : {SmoothingMethod::Mean, SmoothingMethod::Twicing}) {
        REQUIRE(name_of(m) != nullptr);
        CHECK(parse_smoothing_method(name_of(m)) == m);
    }
    for (DiscMode m : {DiscMode::Exact, DiscMode::Fast, DiscMode::Auto}) {
        REQUIRE(name_of(m) != nullptr);
        CHECK(parse_disc_mode(name_of(m)) == m);
    }
    CHECK(std::string(name_of(DetailOrientation::Positive)) == "positive");
    CHECK(std::string(name_of(DetailOrientation::Negative)) == "negative");
    // The spellings are those of the options and of the RDF literals (shapes.ttl).
    CHECK(std::string(name_of(OrientationMode::Both)) == "both");
    CHECK(std::string(name_of(SmoothingMethod::Twicing)) == "twicing");
    CHECK(std::string(name_of(DiscMode::Auto)) == "auto");
    CHECK_FALSE(parse_orientation_mode("Both").has_value());  // exact spelling only
    CHECK_FALSE(parse_disc_mode("").has_value());
    CHECK_FALSE(parse_smoothing_method("twicing ").has_value());
}

TEST_CASE("check_segmentation_params: the defaults pass, each parameter out of range throws",
          "[geometry][segmentation]") {
    CHECK_NOTHROW(check_segmentation_params({}));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<std::function<void(SegmentationParams&)>> bad = {
        [](SegmentationParams& p) { p.radius_rel = 1; },
        [](SegmentationParams& p) { p.radius_rel = 0; },
        [&](SegmentationParams& p) { p.radius = nan; },
        [](SegmentationParams& p) { p.radius = -1; },
        [](SegmentationParams& p) { p.curvature_scale = 1.5; },
        [](SegmentationParams& p) { p.merge_overlap = -0.1; },
        [&](SegmentationParams& p) { p.min_depth_rel = nan; },
        [](SegmentationParams& p) { p.min_faces = 0; },
        [](SegmentationParams& p) { p.clustering.quality_tolerance = 1.5; },
        [](SegmentationParams& p) { p.clustering.quality_tolerance = -0.001; },
        [](SegmentationParams& p) { p.clustering.neighbour_rank = 0; },
    };
    for (std::size_t i = 0; i < bad.size(); ++i) {
        INFO("case " << i);
        SegmentationParams p;
        bad[i](p);
        REQUIRE_THROWS_AS(check_segmentation_params(p), InvalidInput);
    }
    // A radius in mesh units makes radius_rel irrelevant; the ends of the closed ranges pass.
    SegmentationParams p;
    p.radius = 0.5;
    p.radius_rel = 7;
    p.curvature_scale = 0;
    p.merge_overlap = 1;
    p.clustering.quality_tolerance = 1;
    CHECK_NOTHROW(check_segmentation_params(p));
    // run_segmentation checks first.
    SegmentationParams q;
    q.clustering.quality_tolerance = 2;
    REQUIRE_THROWS_WITH(run_segmentation(make_icosphere(2), q),
                        Catch::Contains("quality_tolerance"));
}
