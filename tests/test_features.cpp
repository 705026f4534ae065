#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"
#include "geometry/curvature.hpp"
#include "geometry/feature_table.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

// Features of `texels` of a mesh whose positive depth map is `d`.
FeatureTable table_of(const Mesh& m, const DepthMap& d, const std::vector<Texel>& texels) {
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    const CurvatureField c = make_curvature(m, t, mm.vertex_normal);
    FeatureInputs in;
    in.mesh = &m;
    in.topology = &t;
    in.curvature = &c;
    in.positive_depth = &d;
    in.largest_side = mm.largest_side;
    return make_feature_table(in, texels);
}

// Features of the given texels (face sets) of a mesh, with a zero depth map.
FeatureTable features_of(const Mesh& m, const std::vector<std::vector<int>>& face_sets) {
    DepthMap d;
    d.vertex_depth.assign(m.num_vertices(), 0.0);
    d.face_depth.assign(m.num_faces(), 0.0);
    std::vector<Texel> texels;
    for (const auto& faces : face_sets) {
        Texel x;
        x.faces = faces;
        texels.push_back(x);
    }
    return table_of(m, d, texels);
}

// Features of one texel cut from a mesh by a depth field, as the segmentation cuts it: the
// faces whose depth (mean of their vertex depths) reaches the threshold.
FeatureTable features_of_depth(const Mesh& m, const std::function<double(double, double)>& depth_at,
                               double threshold) {
    DepthMap d;
    for (const auto& p : m.positions) d.vertex_depth.push_back(depth_at(p.x(), p.y()));
    Texel x;
    x.threshold = threshold;
    for (int f = 0; f < m.num_faces(); ++f) {
        const auto& fv = m.faces[f];
        d.face_depth.push_back(
            (d.vertex_depth[fv[0]] + d.vertex_depth[fv[1]] + d.vertex_depth[fv[2]]) / 3);
        if (d.face_depth.back() >= threshold) x.faces.push_back(f);
    }
    d.max_depth = *std::max_element(d.vertex_depth.begin(), d.vertex_depth.end());
    return table_of(m, d, {x});
}

double value(const FeatureTable& t, int row, Feature f) {
    return t.values(row, static_cast<int>(f));
}

// Faces whose barycentre satisfies `inside`.
template <class Pred>
std::vector<int> faces_where(const Mesh& m, Pred inside) {
    std::vector<int> out;
    for (int f = 0; f < m.num_faces(); ++f) {
        const auto& fv = m.faces[f];
        const Eigen::Vector3d c =
            (m.positions[fv[0]] + m.positions[fv[1]] + m.positions[fv[2]]) / 3;
        if (inside(c.x(), c.y())) out.push_back(f);
    }
    return out;
}

}  // namespace

TEST_CASE("feature ids: 20 stable names, looked up both ways", "[geometry][features]") {
    CHECK(kFeatureIds.size() == 20);
    CHECK(kNumClusteringFeatures == 18);  // the paper's features come first
    CHECK(feature_index("contour_sphericity") == static_cast<int>(Feature::ContourSphericity));
    CHECK(feature_index("curvedness_std") == 17);
    CHECK(feature_index("area_rel") == static_cast<int>(Feature::AreaRel));
    CHECK(feature_index("bounding_sphere_radius_rel") == 19);
    CHECK(feature_index("curvature_index") == -1);
}

TEST_CASE("make_feature_table: flat disc", "[geometry][features]") {
    // The whole unit disc, whose bounding box side is 2: in unit-side units its radius is 0.5.
    const Mesh m = test::make_disc(20);
    const FeatureTable t = features_of(m, {test::all_faces(m)});
    // PCA of a flat disc: variances a^2/4, a^2/4, 0 -> 0.5, 0.5, 0.
    CHECK(value(t, 0, Feature::PcaVariance1) == Approx(0.5).margin(0.01));
    CHECK(value(t, 0, Feature::PcaVariance2) == Approx(0.5).margin(0.01));
    CHECK(value(t, 0, Feature::PcaVariance3) == Approx(0.0).margin(1e-9));
    // Smoothed polygonal contour of 120 sides on radius 0.5: perimeter close to pi.
    CHECK(value(t, 0, Feature::ContourPerimeter) == Approx(kPi).epsilon(0.01));
    // Circle: P^2 / A = 4 pi (area of the 120-gon, perimeter of its smoothed contour).
    CHECK(value(t, 0, Feature::Perimeter2AreaRatio) == Approx(4 * kPi).epsilon(0.01));
    // Every contour point at the bounding radius: no spread.
    CHECK(value(t, 0, Feature::ContourSphericity) < 0.01);
    // Flat: zero Gaussian curvature and curvedness.
    CHECK(std::abs(value(t, 0, Feature::GaussianCurvatureMean)) < 1e-6);
    CHECK(std::abs(value(t, 0, Feature::CurvednessMean)) < 1e-6);
    // One texel: the local diameters (all ~ the diameter) are normalised by their maximum.
    CHECK(value(t, 0, Feature::LocalDiameterMean) > 0.97);
    CHECK(value(t, 0, Feature::LocalDiameterStd) < 0.03);
    // Sizes relative to the largest side (2): the 120-gon of radius 1 has area
    // 60 sin(2 pi / 120) = 3.1402, i.e. 0.78504 of the side squared; its radius is 1/2 of it.
    // One texel: the min-max normalised area and radius are 0 (no other detail to compare).
    CHECK(value(t, 0, Feature::AreaRel) == Approx(60 * std::sin(2 * kPi / 120) / 4).epsilon(1e-9));
    CHECK(value(t, 0, Feature::BoundingSphereRadiusRel) == Approx(0.5).epsilon(1e-9));
    CHECK(value(t, 0, Feature::Area) == 0);
}

TEST_CASE("make_feature_table: long strip and square", "[geometry][features]") {
    const Mesh m = test::make_grid(200, 1.0);
    const auto strip = faces_where(
        m, [](double x, double y) { return std::abs(x) < 0.3 && std::abs(y - 0.3) < 0.03; });
    const auto square = faces_where(
        m, [](double x, double y) { return std::abs(x) < 0.1 && std::abs(y + 0.2) < 0.1; });
    const FeatureTable t = features_of(m, {strip, square});
    // A 0.6 x 0.06 rectangle: variances 0.36/12 and 0.0036/12 -> 100/101 and 1/101.
    CHECK(value(t, 0, Feature::PcaVariance1) == Approx(100.0 / 101).epsilon(0.01));
    CHECK(value(t, 0, Feature::PcaVariance2) == Approx(1.0 / 101).epsilon(0.05));
    CHECK(value(t, 1, Feature::PcaVariance1) == Approx(0.5).margin(0.01));
    // Square: P^2/A = 16; a 10:1 strip: (2 * 11)^2 / 10 = 48.4. The (1/4, 1/2, 1/4) contour
    // smoothing cuts each corner and shortens the perimeter by about one grid step per
    // corner (here 1% of the square's perimeter, 2% of P^2), hence 3%.
    CHECK(value(t, 1, Feature::Perimeter2AreaRatio) == Approx(16).epsilon(0.03));
    CHECK(value(t, 0, Feature::Perimeter2AreaRatio) == Approx(48.4).epsilon(0.03));
    // Min-max normalisation over two texels: the larger area is 1, the smaller 0.
    CHECK(value(t, 0, Feature::Area) == Approx(0.0).margin(1e-12));  // 0.036 < 0.04
    CHECK(value(t, 1, Feature::Area) == Approx(1.0));
    // ... while the sizes relative to the side (1 here) keep their meaning: 0.036 and 0.04
    // (faces picked by barycentre on a 0.005 grid: within one row of faces, 3%), and the
    // bounding radii from the area centroid: half-diagonals sqrt(0.3^2 + 0.03^2), 0.1 sqrt(2).
    CHECK(value(t, 0, Feature::AreaRel) == Approx(0.036).epsilon(0.03));
    CHECK(value(t, 1, Feature::AreaRel) == Approx(0.04).epsilon(0.03));
    CHECK(value(t, 0, Feature::BoundingSphereRadiusRel) ==
          Approx(std::hypot(0.3, 0.03)).epsilon(0.03));
    CHECK(value(t, 1, Feature::BoundingSphereRadiusRel) ==
          Approx(0.1 * std::sqrt(2.0)).epsilon(0.03));
    // The square's local diameter spread is below the strip's: the strip has short
    // diameters on its long sides and long ones near its ends.
    CHECK(value(t, 1, Feature::LocalDiameterStd) < value(t, 0, Feature::LocalDiameterStd));
}

TEST_CASE("make_feature_table: contour sphericity of a disc vs a star", "[geometry][features]") {
    const Mesh m = test::make_grid(300, 1.0);
    const auto disc =
        faces_where(m, [](double x, double y) { return std::hypot(x + 0.25, y) < 0.15; });
    const auto star = faces_where(m, [](double x, double y) {
        const double dx = x - 0.25, dy = y;
        const double angle = std::atan2(dy, dx);
        return std::hypot(dx, dy) < 0.15 * (0.6 + 0.4 * std::cos(5 * angle));
    });
    const FeatureTable t = features_of(m, {disc, star});
    CHECK(value(t, 0, Feature::ContourSphericity) < 0.03);
    CHECK(value(t, 1, Feature::ContourSphericity) > 0.15);
    CHECK(value(t, 1, Feature::Perimeter2AreaRatio) > value(t, 0, Feature::Perimeter2AreaRatio));
}

TEST_CASE("make_feature_table: rescaling by 10^k leaves the features unchanged",
          "[geometry][features]") {
    const Mesh m = test::make_sphere(1.0, 4);
    const auto cap = faces_where(m, [](double x, double y) { return std::hypot(x, y) < 0.3; });
    std::vector<int> top;
    for (int f : cap)
        if (m.positions[m.faces[f][0]].z() > 0) top.push_back(f);
    const auto ref = features_of(m, {top});
    // On the unit-side mesh the sphere has radius 0.5: Gaussian curvature 4.
    CHECK(value(ref, 0, Feature::GaussianCurvatureMean) == Approx(4).epsilon(0.03));
    CHECK(value(ref, 0, Feature::ShapeIndexMean) > 0.9);
    for (double k : {1e-3, 1e3}) {
        const auto t = features_of(test::scaled(m, k), {top});
        for (int c = 0; c < kNumFeatures; ++c)
            CHECK(t.values(0, c) == Approx(ref.values(0, c)).epsilon(1e-6).margin(1e-9));
    }
}

TEST_CASE("make_feature_table: preconditions", "[geometry][features]") {
    const Mesh m = test::make_grid(4, 1.0);
    REQUIRE_THROWS_AS(make_feature_table(FeatureInputs{}, {}), InvalidInput);
    // Overlapping texels.
    REQUIRE_THROWS_AS(features_of(m, {{0, 1}, {1, 2}}), InvalidInput);
    REQUIRE_THROWS_AS(features_of(m, {{0, 999}}), InvalidInput);
}

TEST_CASE("make_feature_table: the contour is the depth iso-line, whatever the sampling",
          "[geometry][features]") {
    // A cone of depth 0.3 - r cut at 0.1: the texel is a disc of radius 0.2 on the unit-side
    // grid. The face depths are linear along the segment between two face centres (the cone
    // is linear away from its apex), so the iso-points lie on the circle up to the bending of
    // r along a segment, O(h^2 / rho): the sphericity is 0 and the perimeter 2 pi 0.2 at every
    // grid step, where the vertices of the face staircase are up to a grid step off.
    const auto cone = [](double x, double y) { return std::max(0.0, 0.3 - std::hypot(x, y)); };
    // A square pyramid of depth 0.2 - max(|x|, |y|) cut at 0.1: a square of half side a = 0.1.
    // Its contour radius from the centre is sqrt(a^2 + u^2), u uniform in [-a, a] along each
    // side; with R = a sqrt 2 the sphericity is std(r) / R = sqrt(2/3 - (sqrt 2 + asinh 1)^2 / 8)
    // = 0.0892. R is the bounding radius of the texel's vertices, which lie up to one grid
    // step h outside the iso-line: the sphericity is below the closed form by up to h / a.
    const auto pyramid = [](double x, double y) {
        return std::max(0.0, 0.2 - std::max(std::abs(x), std::abs(y)));
    };
    const double square_closed_form =
        std::sqrt(2.0 / 3 - std::pow(std::sqrt(2.0) + std::asinh(1.0), 2) / 8);
    REQUIRE(square_closed_form == Approx(0.0892).margin(1e-4));
    for (int n : {50, 100, 400}) {
        INFO("grid of " << n << " x " << n << " cells");
        const Mesh m = test::make_grid(n, 1.0);
        const double h = 1.0 / n;
        const FeatureTable disc = features_of_depth(m, cone, 0.1);
        CHECK(value(disc, 0, Feature::ContourSphericity) < 1e-3);
        CHECK(value(disc, 0, Feature::ContourPerimeter) == Approx(2 * kPi * 0.2).epsilon(0.005));
        CHECK(value(disc, 0, Feature::LocalDiameterStd) < 0.01);
        const FeatureTable square = features_of_depth(m, pyramid, 0.1);
        CHECK(value(square, 0, Feature::ContourSphericity) <= square_closed_form * 1.01);
        CHECK(value(square, 0, Feature::ContourSphericity) >= square_closed_form * (1 - h / 0.1));
        // Each corner is cut by the chord between the iso-points of the faces on either side
        // of it, a few tenths of h long: the perimeter 8a is short by less than 2h in all.
        CHECK(value(square, 0, Feature::ContourPerimeter) <= 0.8 + 1e-9);
        CHECK(value(square, 0, Feature::ContourPerimeter) >= 0.8 - 2 * h);
    }
}
