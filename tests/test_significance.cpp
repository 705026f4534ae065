#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "geometry/errors.hpp"
#include "geometry/feature_table.hpp"

using namespace geotex;

namespace {

constexpr int kPerimeter = static_cast<int>(Feature::ContourPerimeter);      // column 0
constexpr int kSphericity = static_cast<int>(Feature::ContourSphericity);    // column 1
constexpr int kDiameterMean = static_cast<int>(Feature::LocalDiameterMean);  // column 2
constexpr int kDiameterStd = static_cast<int>(Feature::LocalDiameterStd);    // column 3
constexpr int kArea = static_cast<int>(Feature::Area);                       // column 4

// Intervals chosen so that each case of the choice shows up in the table below.
const char* const kYaml =
    "scheme: {id: t, version: '1', namespace: 'urn:example:t/', languages: [en], title: {en: T}}\n"
    "features:\n"
    "  contour_perimeter:\n"
    "    - {id: tiny-perimeter, interval: [0, 0.5], labels: {en: tiny perimeter}}\n"
    "    - {id: long-perimeter, interval: [3, 10], labels: {en: long perimeter}}\n"
    "  contour_sphericity:\n"
    "    - {id: circular, interval: [0, 1], labels: {en: circular}}\n"
    "    - {id: non-circular, interval: [1, .inf], labels: {en: non circular}}\n"
    "  local_diameter_mean:\n"
    "    - {id: any-diameter, interval: [-.inf, .inf], labels: {en: any diameter}}\n"
    "  local_diameter_std:\n"
    "    - {id: uniform, interval: [0, 10], labels: {en: uniform}}\n"
    "  area:\n"
    "    - {id: small-area, interval: [0, 2], labels: {en: small area}}\n"
    "    - {id: large-area, interval: [2, .inf], labels: {en: large area}}\n";

const Dictionary& dictionary() {
    static const Dictionary d = parse_dictionary(kYaml, "significance-test");
    return d;
}

/// #texels by 18, every column 0 (constant) unless set.
Eigen::MatrixXd table(int num_texels) { return Eigen::MatrixXd::Zero(num_texels, kNumFeatures); }

/// The score of `feature` in a description.
const FeatureScore& score(const TextureDescription& d, int feature) {
    for (const auto& s : d.features)
        if (s.feature == feature) return s;
    FAIL("feature " << feature << " missing");
    return d.features.front();
}

std::vector<int> chosen_features(const TextureDescription& d) {
    std::vector<int> out;
    for (int i : d.chosen) out.push_back(d.features[static_cast<size_t>(i)].feature);
    return out;
}

// The worked example: 4 texels, texture 0 = {0, 1}, texture 1 = {2, 3}.
//
//   column               texels 0..3     over all           texture 0          texture 1
//   0 contour_perimeter  1  1  3  5      mean 2.5,          V 1, sigma 0,      V 4, sigma 1,
//                                        sigma sqrt(2.75)   S 0                S 1/sqrt(2.75) =
//                                        0.60302
//   1 contour_sphericity 0  0  2  2      mean 1, sigma 1    V 0, S 0           V 2, S 0
//   2 local_diam._mean   .3 .3 .3 .3     sigma 0: constant, S NaN in both (though 0.3 is labelled)
//   3 local_diam._std    2  4  3  3      mean 3,            V 3, sigma 1,      V 3, S 0
//                                        sigma sqrt(0.5)    S 1/sqrt(.5) = 1.41421
//   4 area               1  1  3  5      as column 0: texture 1 ties with column 0 at S 0.60302
//   5..17                0  0  0  0      constant, S NaN
//   (sigma over all of column 0: deviations -1.5 -1.5 0.5 2.5, squares 11, / 4 = 2.75)
//
// Texture 0 ranks (S, then column): perimeter 0, sphericity 0, area 0, diameter std 1.414.
//   perimeter V = 1 lies in no interval ([0, 0.5) and [3, 10) around it): skipped;
//   with n = 3: sphericity (circular), area (small area), diameter std (uniform).
// Texture 1 ranks: sphericity 0, diameter std 0, perimeter 0.603, area 0.603 (tie: column
//   order puts the perimeter first); with n = 3: non circular, uniform, long perimeter.
Eigen::MatrixXd worked_example() {
    Eigen::MatrixXd f = table(4);
    f.col(kPerimeter) << 1, 1, 3, 5;
    f.col(kSphericity) << 0, 0, 2, 2;
    f.col(kDiameterMean).setConstant(0.3);
    f.col(kDiameterStd) << 2, 4, 3, 3;
    f.col(kArea) << 1, 1, 3, 5;
    return f;
}

}  // namespace

TEST_CASE("describe_textures: worked example computed by hand", "[annotation][significance]") {
    DescriptionParams params;
    params.num_concepts = 3;
    const auto d = describe_textures(worked_example(), {0, 0, 1, 1}, 2, dictionary(), params);
    REQUIRE(d.size() == 2);

    const TextureDescription& t0 = d[0];
    CHECK(t0.texture == 0);
    CHECK(t0.num_texels == 2);
    REQUIRE(t0.features.size() == static_cast<size_t>(kNumFeatures));
    CHECK(score(t0, kPerimeter).value == 1);
    CHECK(score(t0, kPerimeter).significance == 0);
    CHECK(score(t0, kPerimeter).rank == 1);
    CHECK(score(t0, kPerimeter).concept_ptr == nullptr);  // outside every interval: skipped
    CHECK_FALSE(score(t0, kPerimeter).chosen);
    CHECK(score(t0, kSphericity).rank == 2);  // S = 0 ties: column order
    CHECK(score(t0, kArea).rank == 3);
    CHECK(score(t0, kDiameterStd).value == 3);
    CHECK(score(t0, kDiameterStd).significance == Approx(std::sqrt(2.0)));
    CHECK(score(t0, kDiameterStd).rank == 4);
    CHECK(chosen_features(t0) == std::vector<int>{kSphericity, kArea, kDiameterStd});
    CHECK(score(t0, kSphericity).concept_ptr->id == "circular");
    CHECK(score(t0, kArea).concept_ptr->id == "small-area");
    CHECK(score(t0, kDiameterStd).concept_ptr->id == "uniform");
    CHECK(t0.note.empty());

    const TextureDescription& t1 = d[1];
    CHECK(score(t1, kSphericity).value == 2);
    CHECK(score(t1, kSphericity).rank == 1);
    CHECK(score(t1, kDiameterStd).significance == 0);
    CHECK(score(t1, kDiameterStd).rank == 2);
    CHECK(score(t1, kPerimeter).value == 4);
    CHECK(score(t1, kPerimeter).significance == Approx(1 / std::sqrt(2.75)));
    CHECK(score(t1, kArea).significance == score(t1, kPerimeter).significance);
    CHECK(score(t1, kPerimeter).rank == 3);  // tie with the area: column order
    CHECK(score(t1, kArea).rank == 4);
    CHECK(chosen_features(t1) == std::vector<int>{kSphericity, kDiameterStd, kPerimeter});
    CHECK(score(t1, kPerimeter).concept_ptr->id == "long-perimeter");
    CHECK(score(t1, kArea).concept_ptr->id == "large-area");  // labelled, but n is reached
    CHECK_FALSE(score(t1, kArea).chosen);
    CHECK(t1.note.empty());
}

TEST_CASE("describe_textures: a constant feature has S NaN, rank 0, and is never chosen",
          "[annotation][significance]") {
    const auto d = describe_textures(worked_example(), {0, 0, 1, 1}, 2, dictionary());
    for (const auto& t : d) {
        const FeatureScore& s = score(t, kDiameterMean);
        CHECK(std::isnan(s.significance));
        CHECK(s.rank == 0);
        CHECK(s.value == 0.3);
        REQUIRE(s.concept_ptr != nullptr);  // 0.3 is in [-.inf, .inf) ...
        CHECK_FALSE(s.chosen);              // ... but an undefined S is never significant
    }
    // the 4 defined features come first by rank, the 14 constant ones after in column order
    const TextureDescription& t0 = d[0];
    for (size_t j = 0; j < t0.features.size(); ++j) {
        INFO(j);
        if (j < 4) {
            CHECK(t0.features[j].rank == static_cast<int>(j) + 1);
        } else {
            CHECK(t0.features[j].rank == 0);
            CHECK(std::isnan(t0.features[j].significance));
            if (j > 4) CHECK(t0.features[j].feature > t0.features[j - 1].feature);
        }
    }
    // n = 5 but only three (texture 0) and four (texture 1) features qualify: a note says so
    CHECK(d[0].chosen.size() == 3);
    CHECK_THAT(d[0].note, Catch::Contains("only 3 of 5 concepts"));
    CHECK(d[1].chosen.size() == 4);
    CHECK_THAT(d[1].note, Catch::Contains("only 4 of 5 concepts"));
}

TEST_CASE("describe_textures: constant up to rounding noise, relative to the magnitude",
          "[annotation][significance]") {
    Eigen::MatrixXd f = worked_example();
    // Gaussian curvature around 1e3 varying in the 13th digit: rounding noise, constant
    f.col(static_cast<int>(Feature::GaussianCurvatureMean)) << 1000, 1000 * (1 + 1e-12), 1000,
        1000 * (1 - 1e-12);
    // a PCA share around 1e-3 varying in the 4th digit: a real spread, however small
    f.col(static_cast<int>(Feature::PcaVariance3)) << 1e-3, 1.001e-3, 1e-3, 1.002e-3;
    const auto d = describe_textures(f, {0, 0, 1, 1}, 2, dictionary());
    CHECK(std::isnan(score(d[0], static_cast<int>(Feature::GaussianCurvatureMean)).significance));
    CHECK_FALSE(std::isnan(score(d[0], static_cast<int>(Feature::PcaVariance3)).significance));
}

TEST_CASE("describe_textures: a one-texel texture ranks by column order, with a note",
          "[annotation][significance]") {
    // texture 0 = {0, 1}, texture 1 = {2}
    // perimeter 1 2 5 (sigma over all > 0), sphericity 0 1 0.5, area 4 4 4 (constant)
    Eigen::MatrixXd f = table(3);
    f.col(kPerimeter) << 1, 2, 5;
    f.col(kSphericity) << 0, 1, 0.5;
    f.col(kArea).setConstant(4);
    const auto d = describe_textures(f, {0, 0, 1}, 2, dictionary());
    const TextureDescription& one = d[1];
    CHECK(one.num_texels == 1);
    // every defined S is 0: perimeter then sphericity, in column order
    CHECK(score(one, kPerimeter).significance == 0);
    CHECK(score(one, kPerimeter).rank == 1);
    CHECK(score(one, kPerimeter).value == 5);
    CHECK(score(one, kSphericity).significance == 0);
    CHECK(score(one, kSphericity).rank == 2);
    CHECK(score(one, kSphericity).value == 0.5);
    CHECK(std::isnan(score(one, kArea).significance));  // constant over all texels
    CHECK(chosen_features(one) == std::vector<int>{kPerimeter, kSphericity});
    CHECK_THAT(one.note, Catch::Contains("one texel"));
    CHECK_THAT(one.note, Catch::Contains("column order"));
    CHECK_THAT(d[0].note, !Catch::Contains("one texel"));
}

TEST_CASE("describe_textures: special cases of the whole table", "[annotation][significance]") {
    SECTION("one texture holding every texel: S = 1 for every defined feature") {
        const auto d = describe_textures(worked_example(), {0, 0, 0, 0}, 1, dictionary());
        CHECK(score(d[0], kPerimeter).significance == 1);
        CHECK(score(d[0], kDiameterStd).significance == 1);
        CHECK(score(d[0], kPerimeter).rank == 1);
        CHECK(score(d[0], kSphericity).rank == 2);
        CHECK_THAT(d[0].note, Catch::Contains("holds every texel"));
    }
    SECTION("a single texel in all: every feature constant, nothing chosen") {
        const auto d = describe_textures(worked_example().topRows(1), {0}, 1, dictionary());
        CHECK(d[0].chosen.empty());
        for (const auto& s : d[0].features) CHECK(s.rank == 0);
        CHECK_THAT(d[0].note, Catch::Contains("every feature is constant"));
    }
    SECTION("no texel, no texture") {
        CHECK(describe_textures(table(0), {}, 0, dictionary()).empty());
    }
    SECTION("a dictionary without concepts: nothing chosen") {
        const auto d = describe_textures(worked_example(), {0, 0, 1, 1}, 2, Dictionary{});
        CHECK(d[0].chosen.empty());
        CHECK(score(d[0], kPerimeter).rank == 1);  // ranks do not depend on the dictionary
        CHECK_THAT(d[0].note, Catch::Contains("only 0 of 5"));
    }
    SECTION("num_concepts = 0") {
        DescriptionParams params;
        params.num_concepts = 0;
        const auto d = describe_textures(worked_example(), {0, 0, 1, 1}, 2, dictionary(), params);
        CHECK(d[0].chosen.empty());
        CHECK(d[0].note.empty());
    }
}

TEST_CASE("describe_textures: deterministic, and S does not depend on units",
          "[annotation][significance]") {
    const Eigen::MatrixXd f = worked_example();
    const auto a = describe_textures(f, {0, 0, 1, 1}, 2, dictionary());
    const auto b = describe_textures(f, {0, 0, 1, 1}, 2, dictionary());
    for (size_t t = 0; t < a.size(); ++t)
        for (size_t j = 0; j < a[t].features.size(); ++j) {
            const FeatureScore& x = a[t].features[j];
            const FeatureScore& y = b[t].features[j];
            CHECK(x.feature == y.feature);
            CHECK(x.rank == y.rank);
            CHECK(x.chosen == y.chosen);
            CHECK((x.significance == y.significance ||
                   (std::isnan(x.significance) && std::isnan(y.significance))));
        }
    // S is a ratio of standard deviations: scaling a feature by 10^k leaves it unchanged
    Eigen::MatrixXd scaled = f;
    scaled.col(kDiameterStd) *= 1e6;
    const auto c = describe_textures(scaled, {0, 0, 1, 1}, 2, dictionary());
    CHECK(score(c[0], kDiameterStd).significance == Approx(std::sqrt(2.0)));
    CHECK(score(c[0], kDiameterStd).value == 3e6);
}

TEST_CASE("describe_textures: mismatched sizes and labels throw InvalidInput",
          "[annotation][significance]") {
    const Eigen::MatrixXd f = worked_example();
    const Dictionary& dict = dictionary();
    REQUIRE_THROWS_AS(describe_textures(f, {0, 0, 1}, 2, dict), InvalidInput);  // 3 labels, 4 rows
    REQUIRE_THROWS_AS(describe_textures(f.leftCols(17), {0, 0, 1, 1}, 2, dict), InvalidInput);
    REQUIRE_THROWS_AS(describe_textures(f, {0, 0, 2, 1}, 2, dict), InvalidInput);   // label >= n
    REQUIRE_THROWS_AS(describe_textures(f, {0, -1, 1, 1}, 2, dict), InvalidInput);  // background
    REQUIRE_THROWS_AS(describe_textures(f, {0, 0, 2, 2}, 3, dict), InvalidInput);   // 1 is empty
    REQUIRE_THROWS_AS(describe_textures(f, {0, 0, 1, 1}, -1, dict), InvalidInput);
    DescriptionParams negative;
    negative.num_concepts = -1;
    REQUIRE_THROWS_AS(describe_textures(f, {0, 0, 1, 1}, 2, dict, negative), InvalidInput);
    Eigen::MatrixXd bad = f;
    bad(2, kArea) = std::nan("");
    REQUIRE_THROWS_AS(describe_textures(bad, {0, 0, 1, 1}, 2, dict), InvalidInput);
    try {
        describe_textures(f, {0, 0, 1}, 2, dict);
    } catch (const InvalidInput& e) {
        CHECK_THAT(std::string(e.what()), Catch::Contains("describe_textures"));
        CHECK_THAT(std::string(e.what()), Catch::Contains("4 rows"));
        CHECK_THAT(std::string(e.what()), Catch::Contains("3 labels"));
    }
}
