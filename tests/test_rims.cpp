#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "common/errors.hpp"
#include "geometry/rims.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/synth.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

// A level-6 sphere (81,920 faces) with two big discs, one raised and one engraved: at r = 4%
// each makes a rim of the other orientation around it with the paper's single smoothing.
SyntheticMesh raised_and_engraved_discs(double engraved_fraction) {
    SynthParams sp;
    sp.level = 6;
    sp.num_big_discs = 2;
    sp.num_small_discs = 0;
    sp.num_squares = 0;
    sp.num_rectangles = 0;
    sp.engraved_fraction = engraved_fraction;
    return make_synthetic_sphere(sp);
}

struct Tally {
    int right = 0;  // texels lying mostly on a shape of their own orientation
    int wrong = 0;  // texels lying mostly on the background or on a shape of the other one
    std::map<int, int> texels_per_shape;  // of the right ones
};

Tally tally(const SyntheticMesh& s, const Segmentation& seg) {
    Tally t;
    for (const Texel& texel : seg.texels) {
        std::map<int, int> votes;
        for (int f : texel.faces) ++votes[s.face_shape[f]];
        int best = -1, most = 0;
        for (const auto& [shape, n] : votes)
            if (n > most) best = shape, most = n;
        const bool negative = texel.orientation == DetailOrientation::Negative;
        if (best >= 0 && s.shapes[best].engraved == negative) {
            ++t.right;
            ++t.texels_per_shape[best];
        } else {
            ++t.wrong;
        }
    }
    return t;
}

Segmentation segment(const SyntheticMesh& s, OrientationMode orientation, bool remove_rims) {
    SegmentationParams p;
    p.radius_rel = 0.04;
    p.orientation = orientation;
    p.remove_rims = remove_rims;
    return run_segmentation(s.mesh, p);
}

}  // namespace

TEST_CASE("run_segmentation: rim removal drops the rims and keeps both discs", "[geometry][rims]") {
    const SyntheticMesh s = raised_and_engraved_discs(0.5);
    REQUIRE(s.shapes.size() == 2);
    REQUIRE(s.shapes[0].engraved != s.shapes[1].engraved);

    // Known answer without the removal: a rim beside each disc (measured: 4 texels, 2 of them
    // rims; the rims cover part of the disc of the other orientation, hence "mostly").
    const Tally kept = tally(s, segment(s, OrientationMode::Both, false));
    CHECK(kept.wrong > 0);

    const Segmentation seg = segment(s, OrientationMode::Both, true);
    const Tally removed = tally(s, seg);
    CHECK(removed.wrong == 0);
    CHECK(removed.right == 2);
    CHECK(removed.texels_per_shape.size() == 2);  // each disc exactly once
    REQUIRE(seg.run_excluded_texels.size() == 2);
    CHECK(seg.run_excluded_texels[0] == 1);  // the engraved disc, left out for the positive run
    CHECK(seg.run_excluded_texels[1] == 1);  // and the raised one for the negative run

    // One orientation alone: only its own disc.
    for (OrientationMode o : {OrientationMode::Positive, OrientationMode::Negative}) {
        const Tally one = tally(s, segment(s, o, true));
        CHECK(one.wrong == 0);
        CHECK(one.right == 1);
    }
}

TEST_CASE("run_segmentation: rim removal changes nothing without details of the other orientation",
          "[geometry][rims]") {
    // Raised discs only: their negative rims are rims, no negative texel is a detail, so the
    // positive run keeps the single smoothing, bit for bit.
    const SyntheticMesh s = raised_and_engraved_discs(0.0);
    const Segmentation a = segment(s, OrientationMode::Positive, false);
    const Segmentation b = segment(s, OrientationMode::Positive, true);
    CHECK(b.run_excluded_texels == std::vector<int>{0});
    CHECK(a.face_texel == b.face_texel);
    REQUIRE(a.texels.size() == b.texels.size());
    for (std::size_t i = 0; i < a.texels.size(); ++i)
        CHECK(a.texels[i].depth_mean == b.texels[i].depth_mean);
}

TEST_CASE("make_rims: rejects a bad radius and mismatched depth maps", "[geometry][rims]") {
    const SyntheticMesh s = raised_and_engraved_discs(0.5);
    const MeshTopology t = make_topology(s.mesh);
    DepthMap pos, neg;
    pos.vertex_depth.assign(s.mesh.num_vertices(), 0.0);
    neg = pos;
    neg.orientation = DetailOrientation::Negative;
    const TexelSet none;
    RimParams p;
    p.radius = 0.1;
    CHECK_NOTHROW(make_rims(s.mesh, t, none, pos, none, neg, p));
    CHECK(make_rims(s.mesh, t, none, pos, none, neg, p).exclude_for_positive.empty());
    REQUIRE_THROWS_AS(make_rims(s.mesh, t, none, neg, none, pos, p),
                      InvalidInput);  // orientations swapped
    DepthMap short_map = pos;
    short_map.vertex_depth.pop_back();
    REQUIRE_THROWS_AS(make_rims(s.mesh, t, none, short_map, none, neg, p), InvalidInput);
    p.radius = 0;
    REQUIRE_THROWS_AS(make_rims(s.mesh, t, none, pos, none, neg, p), InvalidInput);
}

namespace {

// Both depth maps and texel sets of a mesh at r = `radius`, with what rims_possible and
// make_rims take besides.
struct RimInputs {
    MeshTopology topology;
    MeshMetrics metrics;
    SmoothedSurface smoothed;
    DepthMap pos, neg;
    TexelSet pos_set, neg_set;
    RimParams rp;

    RimInputs(const Mesh& m, double radius)
        : topology(make_topology(m)), metrics(make_mesh_metrics(m, topology)) {
        SmoothingParams sp;
        sp.radius = radius;
        smoothed = make_smoothed_surface(m, topology, metrics, sp);
        TexelParams tp;
        tp.radius = radius;
        pos = make_depth_map(m, metrics.vertex_normal, smoothed, DetailOrientation::Positive);
        neg = make_depth_map(m, metrics.vertex_normal, smoothed, DetailOrientation::Negative);
        pos_set = make_texels(m, topology, pos, tp);
        neg_set = make_texels(m, topology, neg, tp);
        rp.radius = radius;
    }
};

double bump(double x, double y, double cx, double cy, double height, double radius) {
    const double d = std::hypot(x - cx, y - cy) / radius;
    return d < 1 ? height * std::pow(std::cos(d * 1.5707963267948966), 2) : 0.0;
}

}  // namespace

TEST_CASE("rims_possible: bounds the other orientation's depth without building it",
          "[geometry][rims]") {
    // Known answers: with an engraved disc beside a raised one, each disc's rim is beside a
    // deeper detail of the other orientation, so a rim is possible either way; with raised
    // discs only, the negative side holds only their rims, shallower than every raised disc.
    for (const double engraved : {0.5, 0.0}) {
        const SyntheticMesh s = raised_and_engraved_discs(engraved);
        const RimInputs in(s.mesh,
                           0.04 * make_mesh_metrics(s.mesh, make_topology(s.mesh)).largest_side);
        REQUIRE(!in.pos_set.texels.empty());
        const bool possible = rims_possible(s.mesh, in.topology, in.metrics.vertex_normal,
                                            in.smoothed, in.pos_set, in.pos, in.rp);
        CHECK(possible == (engraved > 0));
        // The bound agrees with make_rims, which builds both depth maps.
        const Rims rims =
            make_rims(s.mesh, in.topology, in.pos_set, in.pos, in.neg_set, in.neg, in.rp);
        CHECK(rims.exclude_for_positive.empty() == !possible);
        if (engraved > 0)
            CHECK(rims_possible(s.mesh, in.topology, in.metrics.vertex_normal, in.smoothed,
                                in.neg_set, in.neg, in.rp));
    }
}

TEST_CASE("make_rims: a deep rim far from a shallow detail makes no rim of it",
          "[geometry][rims]") {
    // A low bump and, far from it (0.5 against 2r = 0.1), a bump fourteen times higher: the
    // high one's negative rim is deeper than the low bump (measured: 0.0060 against 0.0053),
    // but it lies beyond 2r of the low bump, and each bump's own rim is shallower than that
    // bump. Known answer: no rim. rims_possible sees it too, without the negative depth map:
    // the only vertices whose bound reaches the low bump's depth are beyond 2r of it.
    const Mesh m = test::make_grid(120, 1.0, [](double x, double y) {
        return bump(x, y, -0.25, 0.0, 0.007, 0.04) + bump(x, y, 0.25, 0.0, 0.1, 0.04);
    });
    const RimInputs in(m, 0.05);
    REQUIRE(in.pos_set.texels.size() == 2);
    double shallowest = 1e300, deepest_other = 0;
    for (const Texel& t : in.pos_set.texels) {
        double d = 0;
        for (int f : t.faces)
            for (int v : m.faces[f]) d = std::max(d, in.pos.vertex_depth[v]);
        shallowest = std::min(shallowest, d);
    }
    for (double d : in.neg.vertex_depth) deepest_other = std::max(deepest_other, d);
    REQUIRE(deepest_other > shallowest);
    CHECK_FALSE(rims_possible(m, in.topology, in.metrics.vertex_normal, in.smoothed, in.pos_set,
                              in.pos, in.rp));
    // Within reach of the deep rim (2r = 2 against 0.5), make_rims finds the low bump a rim.
    // But the deep rim is the high bump's own rim, a rim itself, so nothing is left out; and
    // rims_possible sees that too: the nearest raised texel of every vertex that may be the
    // deep rim's deepest is the high bump.
    RimParams wide = in.rp;
    wide.reach_rel = 2 / in.rp.radius;
    const Rims wide_rims = make_rims(m, in.topology, in.pos_set, in.pos, in.neg_set, in.neg, wide);
    CHECK(std::count(wide_rims.positive_rim.begin(), wide_rims.positive_rim.end(), 1) ==
          1);  // the low bump, not the high one
    CHECK(wide_rims.exclude_for_positive.empty());
    CHECK_FALSE(rims_possible(m, in.topology, in.metrics.vertex_normal, in.smoothed, in.pos_set,
                              in.pos, wide));
    const Rims rims = make_rims(m, in.topology, in.pos_set, in.pos, in.neg_set, in.neg, in.rp);
    CHECK(rims.exclude_for_positive.empty());
    CHECK(rims.positive_rim == std::vector<char>(2, 0));
}

TEST_CASE("rims_possible: never says no where make_rims leaves something out", "[geometry][rims]") {
    // A low bump and a dent of growing depth beside it, and a high bump whose deep rim lies
    // within 2r of the low bump: the bound must say "possible" wherever make_rims, with both
    // depth maps, leaves a texel out for the raised details (the dent, once deeper than the
    // low bump), and may say "no" where nothing is left out. Without a dent it must say "no":
    // the deep rim is the high bump's own, and the nearest raised texel of its deepest
    // vertices is the high bump (the part of the bound that tells needs both bumps this close).
    int num_left_out = 0, num_possible = 0;
    for (const double dent : {0.0, 0.002, 0.01, 0.03}) {
        const Mesh m = test::make_grid(120, 1.0, [&](double x, double y) {
            return bump(x, y, -0.1, 0.0, 0.007, 0.04) + bump(x, y, 0.08, 0.0, 0.1, 0.04) -
                   bump(x, y, -0.1, 0.09, dent, 0.03);
        });
        const RimInputs in(m, 0.05);
        REQUIRE(in.pos_set.texels.size() == 2);  // both bumps
        const bool possible = rims_possible(m, in.topology, in.metrics.vertex_normal, in.smoothed,
                                            in.pos_set, in.pos, in.rp);
        const Rims rims = make_rims(m, in.topology, in.pos_set, in.pos, in.neg_set, in.neg, in.rp);
        INFO("dent " << dent);
        if (!rims.exclude_for_positive.empty()) CHECK(possible);
        num_left_out += rims.exclude_for_positive.empty() ? 0 : 1;
        num_possible += possible ? 1 : 0;
        if (dent == 0.0) CHECK_FALSE(possible);  // the high bump's rim is a rim itself
    }
    CHECK(num_left_out >= 2);  // the deep dents are left out: the test reaches both answers
    CHECK(num_possible >= num_left_out);
}

TEST_CASE("rims_possible: no texel, no rim; mismatched inputs are refused", "[geometry][rims]") {
    const SyntheticMesh s = raised_and_engraved_discs(0.0);
    const MeshTopology t = make_topology(s.mesh);
    const MeshMetrics mm = make_mesh_metrics(s.mesh, t);
    SmoothedSurface same;
    same.positions = s.mesh.positions;
    DepthMap zero;
    zero.vertex_depth.assign(s.mesh.num_vertices(), 0.0);
    RimParams rp;
    rp.radius = 0.1;
    CHECK_FALSE(rims_possible(s.mesh, t, mm.vertex_normal, same, TexelSet{}, zero, rp));
    REQUIRE_THROWS_AS(rims_possible(s.mesh, t, mm.vertex_normal, same, TexelSet{}, zero, {}),
                      InvalidInput);  // no radius
    zero.vertex_depth.pop_back();
    REQUIRE_THROWS_AS(rims_possible(s.mesh, t, mm.vertex_normal, same, TexelSet{}, zero, rp),
                      InvalidInput);
}
