// The fit of bounds to marks on textures whose values are set by hand, so that the right
// bounds are known: each texture's texels all have the texture's value unless said otherwise.

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/dictionary_edit.hpp"
#include "annotation/dictionary_fit.hpp"
#include "geometry/feature_table.hpp"
#include "tests/dictionary_fixtures.hpp"

using namespace geotex;
using namespace geotex::test;

namespace {

const std::string kYaml =
    "scheme:\n"
    "  id: fit\n"
    "  version: \"1\"\n"
    "  namespace: \"https://example.org/fit/\"\n"
    "  languages: [en]\n"
    "  title: {en: Fit}\n"
    "facets:\n"
    "  outline:\n"
    "    labels: {en: outline}\n"
    "    features: [contour_sphericity]\n"
    "features:\n"
    "  contour_sphericity:\n"
    "    - id: circular\n"
    "      interval: [0, 0.05]\n"
    "      labels: {en: circular}\n"
    "    - id: close\n"
    "      interval: [0.05, 0.15]\n"
    "      labels: {en: close to circular}\n"
    "    - id: non\n"
    "      interval: [0.15, .inf]\n"
    "      labels: {en: non circular}\n";

const Dictionary& dictionary() {
    static const Dictionary d = parse_dictionary(kYaml, "fit.yaml");
    return d;
}

/// An object whose texture t has the texels `texels[t]`, each the contour sphericity given
/// (the other features 0: constant, so they name nothing).
FitObject object(const std::string& id, const std::vector<std::vector<double>>& texels) {
    FitObject o;
    o.id = id;
    o.num_textures = static_cast<int>(texels.size());
    o.texture_orientation.assign(texels.size(), DetailOrientation::Positive);
    size_t n = 0;
    for (const auto& t : texels) n += t.size();
    o.features = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), kNumFeatures);
    const int col = feature_index("contour_sphericity");
    Eigen::Index row = 0;
    for (size_t t = 0; t < texels.size(); ++t)
        for (double v : texels[t]) {
            o.features(row++, col) = v;
            o.texel_texture.push_back(static_cast<int>(t));
        }
    return o;
}

std::vector<double> five(double v) { return std::vector<double>(5, v); }

// textures 0..4 with values 0.02, 0.08, 0.12, 0.3 and 0.5
FitObject ladder(const std::string& id = "o") {
    return object(id, {five(0.02), five(0.08), five(0.12), five(0.3), five(0.5)});
}

FitMark mark(const std::string& object, int texture, const std::string& concept_id, bool yes,
             const std::string& where = "") {
    return {object, texture, concept_id, yes, where};
}

/// The words of texture `t` with `d`.
std::vector<std::string> words(const FitObject& o, const Dictionary& d, int t) {
    const auto desc = describe_textures(o.features, o.texel_texture, o.num_textures,
                                        o.texture_orientation, d, o.params);
    std::vector<std::string> out;
    for (int i : desc[static_cast<size_t>(t)].chosen)
        out.push_back(
            desc[static_cast<size_t>(t)].features[static_cast<size_t>(i)].concept_ptr->id);
    return out;
}

}  // namespace

TEST_CASE("shortest_decimal_between: fewest digits, nearest the target",
          "[annotation][dictionary_fit]") {
    double v = 0;
    std::string t;
    REQUIRE(shortest_decimal_between(0.08, 0.12, 0.05, v, t));
    CHECK(t == "0.1");
    CHECK(v == 0.1);
    REQUIRE(shortest_decimal_between(0.3, 0.4, 0.15, v, t));
    CHECK(t == "0.31");  // 0.3 and 0.4 are the ends, not between
    REQUIRE(shortest_decimal_between(12.5, 17, 0, v, t));
    CHECK(t == "13");
    REQUIRE(shortest_decimal_between(12.5, 17, 100, v, t));
    CHECK(t == "16");
    REQUIRE(shortest_decimal_between(-0.123, -0.1201, 0, v, t));
    CHECK(t == "-0.121");
    REQUIRE(shortest_decimal_between(150, 260, 0, v, t));
    CHECK(t == "200");
    CHECK(!shortest_decimal_between(1, 1, 0, v, t));
    CHECK(!shortest_decimal_between(1, std::nextafter(1.0, 2.0), 0, v, t));
}

TEST_CASE("fit_dictionary: marks already true move nothing", "[annotation][dictionary_fit]") {
    const auto r = fit_dictionary(dictionary(), {ladder()},
                                  {mark("o", 0, "circular", true), mark("o", 1, "close", true),
                                   mark("o", 3, "circular", false)});
    CHECK(r.edits.empty());
    CHECK(r.unsatisfied.empty());
    CHECK(r.not_reproduced.empty());
}

TEST_CASE("fit_dictionary: well separated yes and no give a shared bound between them",
          "[annotation][dictionary_fit]") {
    // 0.08 should be circular, 0.12 should not: the bound circular|close goes into
    // (0.08, 0.12), the shortest decimal there is 0.1
    const FitObject o = ladder();
    const auto r = fit_dictionary(
        dictionary(), {o}, {mark("o", 1, "circular", true), mark("o", 2, "circular", false)});
    CHECK(r.unsatisfied.empty());
    CHECK(r.not_reproduced.empty());
    REQUIRE(r.edits.size() == 1);
    CHECK(r.edits[0].concept_id == "circular");
    CHECK(r.edits[0].upper);
    CHECK(r.edits[0].value == "0.1");
    // through the YAML: both intervals move, the words follow
    const auto edited = edit_dictionary(kYaml, r.edits);
    REQUIRE(edited.problems.empty());
    const Dictionary d = parse_dictionary(edited.text, "fit.yaml");
    CHECK(d.concepts[0].upper == 0.1);
    CHECK(d.concepts[1].lower == 0.1);
    CHECK(words(o, d, 1) == std::vector<std::string>{"circular"});
    CHECK(words(o, d, 2) == std::vector<std::string>{"close"});
    CHECK(words(o, dictionary(), 1) == std::vector<std::string>{"close"});  // before
}

TEST_CASE("fit_dictionary: a bound moves to the next gap between texture values",
          "[annotation][dictionary_fit]") {
    // 0.3 should be close: close|non moves above 0.3 but below the next texture (0.5)
    const auto r = fit_dictionary(dictionary(), {ladder()}, {mark("o", 3, "close", true)});
    REQUIRE(r.edits.size() == 1);
    CHECK(r.edits[0].concept_id == "close");
    CHECK(r.edits[0].upper);
    CHECK(r.edits[0].value == "0.4");
    CHECK(r.unsatisfied.empty());
    // and downwards: 0.12 should be non circular, the bound goes between 0.08 and 0.12,
    // the nearest to 0.15 of the shortest
    const auto down = fit_dictionary(dictionary(), {ladder()}, {mark("o", 2, "non", true)});
    REQUIRE(down.edits.size() == 1);
    CHECK(down.edits[0].concept_id == "close");
    CHECK(down.edits[0].value == "0.1");
}

TEST_CASE("fit_dictionary: contradictory marks are listed, the others fitted",
          "[annotation][dictionary_fit]") {
    // texture 1 of both objects has 0.08: yes and no for one concept cannot both hold
    const auto r = fit_dictionary(
        dictionary(), {ladder("a"), ladder("b")},
        {mark("a", 1, "circular", true, "m.csv:2"), mark("b", 1, "circular", false, "m.csv:3"),
         mark("a", 3, "close", true, "m.csv:4")});
    REQUIRE(r.unsatisfied.size() == 2);
    CHECK(r.unsatisfied[0].mark.where == "m.csv:2");
    CHECK(r.unsatisfied[1].mark.where == "m.csv:3");
    CHECK(r.unsatisfied[0].reason.find("marked yes and no for 'circular'") != std::string::npos);
    CHECK(r.unsatisfied[0].reason.find("m.csv:3") != std::string::npos);
    REQUIRE(r.edits.size() == 1);
    CHECK(r.edits[0].value == "0.4");
}

TEST_CASE("fit_dictionary: marks no placement satisfies together keep the bounds",
          "[annotation][dictionary_fit]") {
    // 0.3 is non circular, 0.5 is not: the interval [lower, .inf) cannot hold 0.3 without 0.5
    const auto r = fit_dictionary(dictionary(), {ladder()},
                                  {mark("o", 3, "non", true), mark("o", 4, "non", false)});
    CHECK(r.edits.empty());
    REQUIRE(r.unsatisfied.size() == 1);
    CHECK(r.unsatisfied[0].mark.texture == 4);
    CHECK(r.unsatisfied[0].reason.find("no placement") != std::string::npos);
}

TEST_CASE("fit_dictionary: unknown objects, textures and concepts are unsatisfied marks",
          "[annotation][dictionary_fit]") {
    const auto r = fit_dictionary(dictionary(), {ladder()},
                                  {mark("x", 0, "circular", true), mark("o", 9, "circular", true),
                                   mark("o", 0, "round", true)});
    REQUIRE(r.unsatisfied.size() == 3);
    CHECK(r.unsatisfied[0].reason.find("object 'x'") != std::string::npos);
    CHECK(r.unsatisfied[1].reason.find("no texture 9") != std::string::npos);
    CHECK(r.unsatisfied[2].reason == "unknown concept 'round'");
    CHECK(r.edits.empty());
}

TEST_CASE("fit_dictionary: an interval that holds the value, words that still differ",
          "[annotation][dictionary_fit]") {
    // texture 1's mean is 0.12 (close) but no texel of it is in [0.05, 0.15): agreement 0
    const FitObject o = object("o", {five(0.02), {0.0, 0.0, 0.0, 0.3, 0.3}, five(0.5)});
    const auto r = fit_dictionary(dictionary(), {o}, {mark("o", 1, "close", true)});
    CHECK(r.edits.empty());
    CHECK(r.unsatisfied.empty());
    REQUIRE(r.not_reproduced.size() == 1);
    CHECK(r.not_reproduced[0].reason.find("only 0% of the texture's texels") != std::string::npos);
    CHECK(r.not_reproduced[0].reason.find("min_agreement 75%") != std::string::npos);
}
