#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "common/errors.hpp"
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

/// `d` with facets set in code (the YAML loader's facets are tested in test_dictionary.cpp):
/// each list is one facet, in the order of preference.
Dictionary with_facets(Dictionary d, const std::vector<std::vector<int>>& facets) {
    d.facets.clear();
    d.feature_facet.assign(kNumFeatures, -1);
    for (const auto& features : facets) {
        DictionaryFacet f;
        f.id = "facet" + std::to_string(d.facets.size());
        f.features = features;
        for (int i : features)
            d.feature_facet[static_cast<size_t>(i)] = static_cast<int>(d.facets.size());
        d.facets.push_back(f);
    }
    d.declares_facets = true;
    return d;
}

std::vector<TextureDescription> describe(const Eigen::MatrixXd& f, const std::vector<int>& labels,
                                         int n, const Dictionary& d = dictionary(),
                                         const DescriptionParams& p = {}) {
    return describe_textures(f, labels, n, {}, d, p);
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
    DescriptionParams gate;
    gate.max_significance = 0.5;  // the paper's principle as a test: S must set T apart
    const auto d = describe(worked_example(), {0, 0, 1, 1}, 2, dictionary(), gate);
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
    // S <= 0.5 and every texel inside: sphericity and area; the diameter std (S 1.41, more
    // spread in the texture than over all texels) sets nothing apart, though 3 is "uniform".
    CHECK(chosen_features(t0) == std::vector<int>{kSphericity, kArea});
    CHECK(score(t0, kSphericity).concept_ptr->id == "circular");
    CHECK(score(t0, kSphericity).agreement == 1);
    CHECK(score(t0, kArea).concept_ptr->id == "small-area");
    CHECK(score(t0, kDiameterStd).concept_ptr->id == "uniform");
    CHECK_FALSE(score(t0, kDiameterStd).chosen);
    CHECK_FALSE(score(t0, kDiameterStd).withheld);
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
    // the perimeter (S 0.603 > 0.5) is labelled "long perimeter" but does not set texture 1
    // apart; sphericity 2 and diameter std 3 hold for both texels
    CHECK(chosen_features(t1) == std::vector<int>{kSphericity, kDiameterStd});
    CHECK(score(t1, kPerimeter).concept_ptr->id == "long-perimeter");
    CHECK_FALSE(score(t1, kPerimeter).chosen);
    // every texel of both textures has the same value of the chosen features: whatever the
    // resample, the same choice
    for (const auto& t : d)
        for (int i : t.chosen) CHECK(t.features[static_cast<size_t>(i)].stability == 1);

    // Without the test (the default), every concept true of both texels is said: texture 0's
    // diameter std (2 and 4, both "uniform"), texture 1's perimeter (3 and 5, both "long")
    // and area (3 and 5, both "large"), in order of S then column.
    const auto all = describe(worked_example(), {0, 0, 1, 1}, 2);
    CHECK(chosen_features(all[0]) == std::vector<int>{kSphericity, kArea, kDiameterStd});
    CHECK(chosen_features(all[1]) ==
          std::vector<int>{kSphericity, kDiameterStd, kPerimeter, kArea});
}

TEST_CASE("describe_textures: by default a word true of every texture is said of each",
          "[annotation][significance]") {
    // Two textures of discs, both circular (sphericity 0.01-0.04), told apart by their area.
    // S of the sphericity is 0.86 and 1.1: it sets neither apart, yet both are circular,
    // and a collection asking for circular details must find them whatever else the object
    // holds. With the paper's significance test (S <= 0.5) neither would be called circular.
    Eigen::MatrixXd f = table(12);
    f.col(kSphericity) << 0.01, 0.02, 0.03, 0.04, 0.01, 0.04, 0.01, 0.02, 0.03, 0.04, 0.02, 0.03;
    f.col(kArea) << 0.1, 0.2, 0.1, 0.2, 0.1, 0.2, 5, 6, 5, 6, 5, 6;
    const std::vector<int> labels{0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1};
    const auto d = describe(f, labels, 2);
    for (const auto& t : d) {
        CHECK(score(t, kSphericity).significance > 0.8);
        CHECK(score(t, kSphericity).chosen);
        CHECK(score(t, kSphericity).concept_ptr->id == "circular");
    }
    DescriptionParams gate;
    gate.max_significance = 0.5;
    for (const auto& t : describe(f, labels, 2, dictionary(), gate))
        CHECK_FALSE(score(t, kSphericity).chosen);
}

TEST_CASE("describe_textures: a constant feature has S NaN, rank 0, and is never chosen",
          "[annotation][significance]") {
    const auto d = describe(worked_example(), {0, 0, 1, 1}, 2);
    for (const auto& t : d) {
        const FeatureScore& s = score(t, kDiameterMean);
        CHECK(std::isnan(s.significance));
        CHECK(s.rank == 0);
        CHECK(s.value == 0.3);
        REQUIRE(s.concept_ptr != nullptr);  // 0.3 is in [-.inf, .inf) ...
        CHECK_FALSE(s.chosen);              // ... but an undefined S is never significant
    }
    // the 4 defined features come first by rank, the constant ones after in column order
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
}

TEST_CASE("describe_textures: constant up to rounding noise, relative to the magnitude",
          "[annotation][significance]") {
    Eigen::MatrixXd f = worked_example();
    // Gaussian curvature around 1e3 varying in the 13th digit: rounding noise, constant
    f.col(static_cast<int>(Feature::GaussianCurvatureMean)) << 1000, 1000 * (1 + 1e-12), 1000,
        1000 * (1 - 1e-12);
    // a PCA share around 1e-3 varying in the 4th digit: a real spread, however small
    f.col(static_cast<int>(Feature::PcaVariance3)) << 1e-3, 1.001e-3, 1e-3, 1.002e-3;
    const auto d = describe(f, {0, 0, 1, 1}, 2);
    CHECK(std::isnan(score(d[0], static_cast<int>(Feature::GaussianCurvatureMean)).significance));
    CHECK_FALSE(std::isnan(score(d[0], static_cast<int>(Feature::PcaVariance3)).significance));
}

TEST_CASE("describe_textures: a one-texel texture is named by its own values",
          "[annotation][significance]") {
    // texture 0 = {0, 1}, texture 1 = {2}
    // perimeter 1 2 5 (sigma over all > 0), sphericity 0 1 0.5, area 4 4 4 (constant)
    Eigen::MatrixXd f = table(3);
    f.col(kPerimeter) << 1, 2, 5;
    f.col(kSphericity) << 0, 1, 0.5;
    f.col(kArea).setConstant(4);
    const auto d = describe(f, {0, 0, 1}, 2);
    const TextureDescription& one = d[1];
    CHECK(one.num_texels == 1);
    CHECK(score(one, kPerimeter).significance == 0);
    CHECK(score(one, kPerimeter).rank == 1);
    CHECK(score(one, kPerimeter).value == 5);
    CHECK(score(one, kSphericity).significance == 0);
    CHECK(score(one, kSphericity).rank == 2);
    CHECK(std::isnan(score(one, kArea).significance));  // constant over all texels
    // perimeter 5 is "long perimeter", sphericity 0.5 "circular": both hold for the texel
    CHECK(chosen_features(one) == std::vector<int>{kPerimeter, kSphericity});
    CHECK_THAT(one.note, Catch::Contains("one texel"));
    CHECK_THAT(d[0].note, !Catch::Contains("one texel"));
    // texture 0: sphericity 0 and 1 straddle the bound 1 of "circular": half its texels only
    CHECK(score(d[0], kSphericity).concept_ptr->id == "circular");  // the mean 0.5
    CHECK(score(d[0], kSphericity).agreement == 0.5);
    CHECK_FALSE(score(d[0], kSphericity).chosen);
}

TEST_CASE("describe_textures: a concept must hold for most texels, not only for the mean",
          "[annotation][significance]") {
    // texture 0: sphericity 0.1 0.1 0.1 5.0: mean 1.325, "non circular", true of one texel in
    // four; texture 1 far away, so that S is small.
    Eigen::MatrixXd f = table(8);
    f.col(kSphericity) << 0.1, 0.1, 0.1, 5.0, 50, 50, 50, 50;
    const auto d = describe(f, {0, 0, 0, 0, 1, 1, 1, 1}, 2);
    const FeatureScore& s = score(d[0], kSphericity);
    CHECK(s.significance < 0.5);
    CHECK(s.concept_ptr->id == "non-circular");
    CHECK(s.agreement == 0.25);
    CHECK_FALSE(s.chosen);
    DescriptionParams lenient;
    lenient.min_agreement = 0.25;
    lenient.min_stability = 0;
    CHECK(score(describe(f, {0, 0, 0, 0, 1, 1, 1, 1}, 2, dictionary(), lenient)[0], kSphericity)
              .chosen);
}

TEST_CASE("describe_textures: one concept per facet, the dictionary's order of preference",
          "[annotation][significance]") {
    // two well separated textures of 6 texels; perimeter, sphericity and area all qualify
    Eigen::MatrixXd f = table(12);
    f.col(kPerimeter) << 0.1, 0.2, 0.1, 0.2, 0.1, 0.2, 5, 6, 5, 6, 5, 6;
    f.col(kSphericity) << 0.1, 0.2, 0.1, 0.2, 0.1, 0.2, 5, 6, 5, 6, 5, 6;
    f.col(kArea) << 0.1, 0.2, 0.1, 0.2, 0.1, 0.2, 5, 6, 5, 6, 5, 6;
    const std::vector<int> labels{0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1};
    const auto each_own = describe(f, labels, 2);  // no facets: each feature its own
    CHECK(chosen_features(each_own[0]) == std::vector<int>{kPerimeter, kSphericity, kArea});

    const Dictionary grouped = with_facets(dictionary(), {{kArea, kPerimeter}, {kSphericity}});
    const auto d = describe(f, labels, 2, grouped);
    // the facet {area, perimeter} says "small area" (first in its order), never both
    CHECK(chosen_features(d[0]) == std::vector<int>{kSphericity, kArea});
    CHECK(chosen_features(d[1]) == std::vector<int>{kSphericity, kArea});
    CHECK(score(d[0], kArea).facet == 0);
    CHECK(score(d[0], kPerimeter).facet == 0);
    CHECK(score(d[0], kSphericity).facet == 1);
    CHECK(score(d[0], kDiameterStd).facet == -1);  // in no facet of this dictionary
    for (const auto& t : d) {
        std::vector<int> per_facet(grouped.facets.size(), 0);
        for (int i : t.chosen)
            ++per_facet[static_cast<size_t>(t.features[static_cast<size_t>(i)].facet)];
        for (int n : per_facet) CHECK(n <= 1);
    }
    // reversed preference: the perimeter speaks for the facet
    const auto r =
        describe(f, labels, 2, with_facets(dictionary(), {{kPerimeter, kArea}, {kSphericity}}));
    CHECK(chosen_features(r[0]) == std::vector<int>{kPerimeter, kSphericity});
    // max_concepts keeps the most significant facets (here all S are equal: column order)
    DescriptionParams one;
    one.max_concepts = 1;
    const auto capped = describe(f, labels, 2, grouped, one);
    CHECK(capped[0].chosen.size() == 1);
    CHECK(capped[0].withheld.size() == 1);
}

TEST_CASE("describe_textures: a concept restricted to a relief never names the other one",
          "[annotation][significance]") {
    Dictionary d = with_facets(dictionary(), {{kSphericity, kArea}});
    for (auto& c : d.concepts)
        if (c.id == "circular") c.relief = Relief::Raised;  // think "dome"
    Eigen::MatrixXd f = table(8);
    f.col(kSphericity) << 0.5, 0.5, 0.5, 0.5, 20, 20, 20, 20;
    f.col(kArea) << 1, 1, 1, 1, 9, 9, 9, 9;
    const std::vector<int> labels{0, 0, 0, 0, 1, 1, 1, 1};
    const auto raised = describe_textures(
        f, labels, 2, {DetailOrientation::Positive, DetailOrientation::Positive}, d);
    CHECK(chosen_features(raised[0]) == std::vector<int>{kSphericity});
    const auto engraved = describe_textures(
        f, labels, 2, {DetailOrientation::Negative, DetailOrientation::Positive}, d);
    CHECK(engraved[0].orientation == DetailOrientation::Negative);
    // not "circular": the facet falls back on its next feature
    CHECK(chosen_features(engraved[0]) == std::vector<int>{kArea});
    CHECK_FALSE(score(engraved[0], kSphericity).chosen);
}

TEST_CASE("describe_textures: a choice that flips under resampling is withheld",
          "[annotation][significance]") {
    // texture 0: sphericity 0.9 (6 texels) and 1.2 (2 texels): mean 0.975 in "circular" [0, 1),
    // true of 6 of 8 texels = min_agreement. A resample with 3 or more of the 1.2s loses that:
    // P(X <= 2), X ~ Binomial(8, 1/4), = 0.679 of the resamples keep it. Texture 1 far away.
    Eigen::MatrixXd f = table(16);
    f.col(kSphericity) << 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 1.2, 1.2, 30, 31, 30, 31, 30, 31, 30, 31;
    std::vector<int> labels(16, 1);
    for (int i = 0; i < 8; ++i) labels[static_cast<size_t>(i)] = 0;
    const auto d = describe(f, labels, 2);
    const FeatureScore& s = score(d[0], kSphericity);
    CHECK(s.concept_ptr->id == "circular");
    CHECK(s.agreement == 0.75);
    // 200 resamples: the share's standard error is sqrt(0.679 * 0.321 / 200) = 0.033
    CHECK(s.stability > 0.679 - 4 * 0.033);
    CHECK(s.stability < 0.679 + 4 * 0.033);
    CHECK(s.withheld);
    CHECK_FALSE(s.chosen);
    CHECK(d[0].withheld.size() == 1);
    CHECK_THAT(d[0].note, Catch::Contains("withheld"));
    // texture 1 (30 and 31, all "non circular"): stable
    CHECK(score(d[1], kSphericity).chosen);
    CHECK(score(d[1], kSphericity).stability == 1);
    // a lower bar asserts it, and no resampling asserts whatever the rule picks
    DescriptionParams lower;
    lower.min_stability = 0.5;
    CHECK(score(describe(f, labels, 2, dictionary(), lower)[0], kSphericity).chosen);
    DescriptionParams none;
    none.num_resamples = 0;
    CHECK(score(describe(f, labels, 2, dictionary(), none)[0], kSphericity).chosen);
}

TEST_CASE("describe_textures: the same description whatever the order of the texels",
          "[annotation][significance]") {
    // 3 textures of 10 texels with spread values; permuting the rows (labels along) must
    // give bit-identical values, S, agreements, stabilities and choices.
    Eigen::MatrixXd f = table(30);
    std::vector<int> labels(30);
    for (int t = 0; t < 30; ++t) {
        const int k = t % 3;
        labels[static_cast<size_t>(t)] = k;
        f(t, kPerimeter) = 0.2 + 3.0 * k + 0.037 * ((t * 7) % 11);
        f(t, kSphericity) = 0.6 + 0.5 * k + 0.05 * ((t * 5) % 13);
        f(t, kArea) = 1.9 + 0.01 * k + 0.02 * ((t * 3) % 7);
        f(t, kDiameterStd) = 2.0 + 3.0 * k + 0.1 * ((t * 11) % 5);
    }
    std::vector<int> order(30);
    for (int i = 0; i < 30; ++i)
        order[static_cast<size_t>(i)] = (i * 17 + 5) % 30;  // a permutation
    Eigen::MatrixXd g(30, kNumFeatures);
    std::vector<int> permuted(30);
    for (int i = 0; i < 30; ++i) {
        g.row(i) = f.row(order[static_cast<size_t>(i)]);
        permuted[static_cast<size_t>(i)] =
            labels[static_cast<size_t>(order[static_cast<size_t>(i)])];
    }
    const auto a = describe(f, labels, 3);
    const auto b = describe(g, permuted, 3);
    bool some_chosen = false, some_unstable = false;
    for (size_t k = 0; k < a.size(); ++k) {
        CHECK(a[k].chosen == b[k].chosen);
        CHECK(a[k].withheld == b[k].withheld);
        some_chosen = some_chosen || !a[k].chosen.empty();
        for (size_t j = 0; j < a[k].features.size(); ++j) {
            const FeatureScore& x = a[k].features[j];
            const FeatureScore& y = b[k].features[j];
            CHECK(x.feature == y.feature);
            CHECK(x.value == y.value);
            CHECK((x.significance == y.significance ||
                   (std::isnan(x.significance) && std::isnan(y.significance))));
            CHECK(x.agreement == y.agreement);
            CHECK(x.stability == y.stability);
            some_unstable = some_unstable || (x.stability > 0 && x.stability < 1);
        }
    }
    CHECK(some_chosen);
    CHECK(some_unstable);  // the resampling is exercised, not only trivial cases
}

TEST_CASE("describe_textures: special cases of the whole table", "[annotation][significance]") {
    SECTION("one texture holding every texel: S = 1, the concepts that hold for most texels") {
        const auto d = describe(worked_example(), {0, 0, 0, 0}, 1);
        CHECK(score(d[0], kPerimeter).significance == 1);
        CHECK(score(d[0], kDiameterStd).significance == 1);
        CHECK(score(d[0], kPerimeter).rank == 1);
        CHECK(score(d[0], kSphericity).rank == 2);
        CHECK_THAT(d[0].note, Catch::Contains("holds every texel"));
        // diameter std 2 4 3 3: all "uniform" [0, 10); sphericity 0 0 2 2: half circular
        CHECK(score(d[0], kDiameterStd).chosen);
        CHECK_FALSE(score(d[0], kSphericity).chosen);
    }
    SECTION("a single texel in all: every feature constant, nothing chosen") {
        const auto d = describe(worked_example().topRows(1), {0}, 1);
        CHECK(d[0].chosen.empty());
        for (const auto& s : d[0].features) CHECK(s.rank == 0);
        CHECK_THAT(d[0].note, Catch::Contains("every feature is constant"));
    }
    SECTION("no texel, no texture") { CHECK(describe(table(0), {}, 0).empty()); }
    SECTION("a dictionary without concepts: nothing chosen") {
        const auto d = describe(worked_example(), {0, 0, 1, 1}, 2, Dictionary{});
        CHECK(d[0].chosen.empty());
        CHECK(score(d[0], kPerimeter).rank == 1);  // ranks do not depend on the dictionary
        CHECK(score(d[0], kPerimeter).facet == -1);
    }
}

TEST_CASE("describe_textures: deterministic, and S does not depend on units",
          "[annotation][significance]") {
    const Eigen::MatrixXd f = worked_example();
    const auto a = describe(f, {0, 0, 1, 1}, 2);
    const auto b = describe(f, {0, 0, 1, 1}, 2);
    for (size_t t = 0; t < a.size(); ++t)
        for (size_t j = 0; j < a[t].features.size(); ++j) {
            const FeatureScore& x = a[t].features[j];
            const FeatureScore& y = b[t].features[j];
            CHECK(x.feature == y.feature);
            CHECK(x.rank == y.rank);
            CHECK(x.chosen == y.chosen);
            CHECK(x.stability == y.stability);
            CHECK((x.significance == y.significance ||
                   (std::isnan(x.significance) && std::isnan(y.significance))));
        }
    // S is a ratio of standard deviations: scaling a feature by 10^k leaves it unchanged
    Eigen::MatrixXd scaled = f;
    scaled.col(kDiameterStd) *= 1e6;
    const auto c = describe(scaled, {0, 0, 1, 1}, 2);
    CHECK(score(c[0], kDiameterStd).significance == Approx(std::sqrt(2.0)));
    CHECK(score(c[0], kDiameterStd).value == 3e6);
}

TEST_CASE("describe_textures: mismatched sizes, labels and parameters throw InvalidInput",
          "[annotation][significance]") {
    const Eigen::MatrixXd f = worked_example();
    const Dictionary& dict = dictionary();
    REQUIRE_THROWS_AS(describe(f, {0, 0, 1}, 2), InvalidInput);  // 3 labels, 4 rows
    REQUIRE_THROWS_AS(describe(f.leftCols(kNumFeatures - 1), {0, 0, 1, 1}, 2), InvalidInput);
    REQUIRE_THROWS_AS(describe(f, {0, 0, 2, 1}, 2), InvalidInput);   // label >= n
    REQUIRE_THROWS_AS(describe(f, {0, -1, 1, 1}, 2), InvalidInput);  // background
    REQUIRE_THROWS_AS(describe(f, {0, 0, 2, 2}, 3), InvalidInput);   // 1 is empty
    REQUIRE_THROWS_AS(describe(f, {0, 0, 1, 1}, -1), InvalidInput);
    REQUIRE_THROWS_AS(describe_textures(f, {0, 0, 1, 1}, 2, {DetailOrientation::Positive}, dict),
                      InvalidInput);  // one orientation for two textures
    const auto bad_params = [&](auto set) {
        DescriptionParams p;
        set(p);
        return describe(f, {0, 0, 1, 1}, 2, dict, p);
    };
    REQUIRE_THROWS_AS(bad_params([](DescriptionParams& p) { p.max_concepts = -1; }), InvalidInput);
    REQUIRE_THROWS_AS(bad_params([](DescriptionParams& p) { p.max_significance = -0.5; }),
                      InvalidInput);
    REQUIRE_THROWS_AS(bad_params([](DescriptionParams& p) { p.max_significance = std::nan(""); }),
                      InvalidInput);
    REQUIRE_THROWS_AS(bad_params([](DescriptionParams& p) { p.min_agreement = std::nan(""); }),
                      InvalidInput);
    REQUIRE_THROWS_AS(bad_params([](DescriptionParams& p) { p.min_agreement = 1.5; }),
                      InvalidInput);
    REQUIRE_THROWS_AS(bad_params([](DescriptionParams& p) { p.min_stability = -0.1; }),
                      InvalidInput);
    REQUIRE_THROWS_AS(bad_params([](DescriptionParams& p) { p.num_resamples = -1; }), InvalidInput);
    Eigen::MatrixXd bad = f;
    bad(2, kArea) = std::nan("");
    REQUIRE_THROWS_AS(describe(bad, {0, 0, 1, 1}, 2), InvalidInput);
    try {
        describe(f, {0, 0, 1}, 2);
        FAIL("no exception");
    } catch (const InvalidInput& e) {
        CHECK_THAT(std::string(e.what()), Catch::Contains("describe_textures"));
        CHECK_THAT(std::string(e.what()), Catch::Contains("4 rows"));
        CHECK_THAT(std::string(e.what()), Catch::Contains("3 labels"));
    }
}
