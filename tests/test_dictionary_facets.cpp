#include <catch2/catch.hpp>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "tests/dictionary_fixtures.hpp"

using namespace geotex;
using namespace geotex::test;

// ---- facets and relief --------------------------------------------------------------------

TEST_CASE("parse_dictionary: facets in the YAML's order, their features in the curator's order",
          "[annotation][dictionary][facets]") {
    const auto problems = check_dictionary(kFaceted);
    INFO(listing(problems));
    REQUIRE(problems.empty());
    const Dictionary d = parse_dictionary(kFaceted, "faceted.yaml");
    CHECK(d.declares_facets);
    CHECK(d.warnings.empty());
    REQUIRE(d.facets.size() == 3);
    const DictionaryFacet& outline = d.facets[0];
    CHECK(outline.id == "outline");
    CHECK(outline.labels ==
          std::map<std::string, std::string>{{"en", "outline"}, {"fr", "contour"}});
    CHECK(outline.features ==
          std::vector<int>{column_of("perimeter2_area_ratio"), column_of("contour_sphericity")});
    CHECK(outline.line == 8);
    CHECK(outline.column == 3);
    CHECK(d.facets[1].id == "size");
    CHECK(d.facets[1].features == std::vector<int>{column_of("area_rel"), column_of("area")});
    CHECK(d.facets[1].line == 11);
    CHECK(d.facets[2].id == "surface");
    CHECK(d.facets[2].labels.at("fr") == "forme de la surface");
    CHECK(d.facets[2].features == std::vector<int>{column_of("shape_index_mean")});

    REQUIRE(d.feature_facet.size() == static_cast<size_t>(kNumFeatures));
    std::vector<int> expected(kNumFeatures, -1);
    expected[static_cast<size_t>(column_of("perimeter2_area_ratio"))] = 0;
    expected[static_cast<size_t>(column_of("contour_sphericity"))] = 0;
    expected[static_cast<size_t>(column_of("area_rel"))] = 1;
    expected[static_cast<size_t>(column_of("area"))] = 1;
    expected[static_cast<size_t>(column_of("shape_index_mean"))] = 2;
    CHECK(d.feature_facet == expected);

    // relief: engraved, raised, and absent (any detail)
    std::map<std::string, Relief> relief;
    for (const auto& c : d.concepts) relief[c.id] = c.relief;
    CHECK(relief.at("spherical-cup") == Relief::Engraved);
    CHECK(relief.at("dome") == Relief::Raised);
    CHECK(relief.at("saddle") == Relief::Any);
    CHECK(relief.at("circular-shape") == Relief::Any);
}

TEST_CASE("parse_dictionary: an older dictionary without facets loads, one facet per feature",
          "[annotation][dictionary][facets]") {
    const Dictionary d = parse_dictionary(kClean, "old.yaml");
    CHECK_FALSE(d.declares_facets);
    REQUIRE(d.warnings.size() == 1);
    CHECK(d.warnings[0].line == 1);
    CHECK(d.warnings[0].column == 1);
    CHECK_THAT(d.warnings[0].message,
               Catch::StartsWith("no facets: each feature is its own facet, so a texture may "
                                 "get several concepts of one kind"));
    // in column order: contour_sphericity (1), then area (4); named by the feature id in every
    // required language, placed at the feature's key
    REQUIRE(d.facets.size() == 2);
    CHECK(d.facets[0].id == "contour_sphericity");
    CHECK(d.facets[0].labels == std::map<std::string, std::string>{{"en", "contour_sphericity"},
                                                                   {"fr", "contour_sphericity"}});
    CHECK(d.facets[0].features == std::vector<int>{column_of("contour_sphericity")});
    CHECK(d.facets[0].line == 12);
    CHECK(d.facets[0].column == 3);
    CHECK(d.facets[1].id == "area");
    CHECK(d.facets[1].features == std::vector<int>{column_of("area")});
    CHECK(d.facets[1].line == 8);
    std::vector<int> expected(kNumFeatures, -1);
    expected[static_cast<size_t>(column_of("contour_sphericity"))] = 0;
    expected[static_cast<size_t>(column_of("area"))] = 1;
    CHECK(d.feature_facet == expected);
    // a warning is not a problem
    CHECK(check_dictionary(kClean).empty());
}

TEST_CASE("check_dictionary: two concepts with one label in one language name both places",
          "[annotation][dictionary][facets]") {
    // the later label is reported, with the earlier one's line and column; ASCII case aside
    require_one(edit(kFaceted, "{en: dome, fr: dôme}", "{en: Spherical Cup, fr: dôme}"), 41, 20,
                "concept 'dome': label 'Spherical Cup' in 'en' is also the label of concept "
                "'spherical-cup' at line 37, column 20; two concepts with one label cannot be "
                "told apart");
    // columns count characters: "é" before the French label is one column
    require_one(edit(kFaceted, "{en: dome, fr: dôme}", "{en: dome, fr: cuvette sphérique}"), 41, 30,
                "label 'cuvette sphérique' in 'fr' is also the label of concept "
                "'spherical-cup' at line 37, column 39");
    // concepts of different features too (the old default's four "flat region")
    require_one(edit(kFaceted, "{en: tiny detail,", "{en: small area,"), 33, 20,
                "concept 'tiny-detail': label 'small area' in 'en' is also the label of concept "
                "'small-area' at line 21, column 20");
    // one text in two languages is two labels, not a clash
    CHECK(
        check_dictionary(edit(kFaceted, "{en: dome, fr: dôme}", "{en: dome, fr: saddle}")).empty());
    // two facets with one label
    require_one(edit(kFaceted, "{en: size, fr: taille}", "{en: Outline, fr: taille}"), 12, 18,
                "facet 'size': label 'Outline' in 'en' is also the label of facet 'outline' at "
                "line 9, column 18");
}

TEST_CASE("check_dictionary: a facet with the label of a concept, a SKOS top concept too",
          "[annotation][dictionary][facets]") {
    // reported at the facet's label, naming the concept's; ASCII case aside
    require_one(edit(kFaceted, "{en: size, fr: taille}", "{en: Small Area, fr: taille}"), 12, 18,
                "facet 'size': label 'Small Area' in 'en' is also the label of concept "
                "'small-area' at line 21, column 20; a facet is a concept of the scheme too");
    require_one(edit(kFaceted, "{en: outline, fr: contour}", "{en: outline, fr: forme circulaire}"),
                9, 31,
                "facet 'outline': label 'forme circulaire' in 'fr' is also the label of "
                "concept 'circular-shape' at line 25, column 40");
    // one text as the facet's label in one language and a concept's in another is no clash
    CHECK(check_dictionary(edit(kFaceted, "{en: size, fr: taille}", "{en: size, fr: small area}"))
              .empty());
    // Without `facets`, each feature is a facet labelled by its id: a concept with that label
    // is reported at its label.
    require_one(edit(kClean, "{en: small area, fr: petite aire}", "{en: Area, fr: petite aire}"),
                11, 20,
                "concept 'small-area': label 'Area' in 'en' is also the label of the facet that a "
                "dictionary without 'facets' makes of feature 'area'");
}

TEST_CASE("check_dictionary: a feature with concepts in no facet",
          "[annotation][dictionary][facets]") {
    // reported at the feature's key under `features`
    require_one(edit(kFaceted, "[shape_index_mean]", "[pca_variance_1]"), 34, 3,
                "feature 'shape_index_mean' has concepts but is in no facet");
    // a feature without concepts may be left out of the facets
    CHECK(check_dictionary(edit(kFaceted,
                                "  area_rel:\n    - id: tiny-detail\n"
                                "      interval: [0, 0.0002]\n"
                                "      labels: {en: tiny detail, fr: détail minuscule}\n",
                                "  area_rel: []\n"))
              .empty());
    // an empty `facets` is one problem, not one per feature
    const std::string facets = kFaceted.substr(
        kFaceted.find("facets:"), kFaceted.find("features:\n  area:") - kFaceted.find("facets:"));
    require_one(edit(kFaceted, facets, "facets: {}\n"), 7, 9, "facets is empty");
}

TEST_CASE("check_dictionary: a feature in two facets, or twice in one",
          "[annotation][dictionary][facets]") {
    require_each(kFaceted, {{"[shape_index_mean]", "[shape_index_mean, area]", 16, 34,
                             "feature 'area' is in two facets: facet 'surface' here and 'size' at "
                             "line 13, column 26; a feature belongs to one facet"},
                            {"[area_rel, area]", "[area_rel, area, area_rel]", 13, 32,
                             "facet 'size' lists 'area_rel' twice (first at line 13, column 16)"}});
}

TEST_CASE("check_dictionary: an unknown feature in a facet, with the closest id",
          "[annotation][dictionary][facets]") {
    require_each(kFaceted,
                 {{"[area_rel, area]", "[area_rel, area, contour_sphericty]", 13, 32,
                   "unknown feature 'contour_sphericty' in facet 'size'; did you mean "
                   "'contour_sphericity'?"},
                  {"[area_rel, area]", "[area_rel, area, colour]", 13, 32,
                   "unknown feature 'colour' in facet 'size' (the 20 feature ids are listed"},
                  {"[area_rel, area]", "[area_rel, area, [depth_mean]]", 13, 32,
                   "facet 'size': a feature id must be a text, found a list"}});
}

TEST_CASE("check_dictionary: a facet without features", "[annotation][dictionary][facets]") {
    // an empty list; its feature is then in no facet, which is reported too
    const auto problems = check_dictionary(edit(kFaceted, "[shape_index_mean]", "[]"));
    INFO(listing(problems));
    REQUIRE(problems.size() == 2);
    CHECK(problems[0].line == 16);
    CHECK(problems[0].column == 15);
    CHECK_THAT(problems[0].message,
               Catch::Contains("facet 'surface' has no features: list the features"));
    CHECK(problems[1].line == 34);
    CHECK_THAT(problems[1].message,
               Catch::Contains("'shape_index_mean' has concepts but is in no"));
    // nothing after the key: reported at the key
    const std::string no_list =
        edit(edit(kFaceted, "    features: [shape_index_mean]\n", "    features:\n"),
             "[perimeter2_area_ratio, contour_sphericity]",
             "[perimeter2_area_ratio, contour_sphericity, shape_index_mean]");
    require_one(no_list, 16, 5, "facet 'surface' has no features");
    // no key at all
    require_one(edit(no_list, "    features:\n", ""), 15, 5,
                "facet 'surface': missing required key 'features'");
}

TEST_CASE("check_dictionary: a facet label missing in a required language",
          "[annotation][dictionary][facets]") {
    require_each(kFaceted, {{"{en: size, fr: taille}", "{en: size}", 12, 13,
                             "facet 'size': labels: no text in 'fr' (every language listed in "
                             "scheme.languages is required)"},
                            {"    labels: {en: size, fr: taille}\n", "", 12, 5,
                             "facet 'size': missing required key 'labels'"}});
}

TEST_CASE("check_dictionary: unknown relief values", "[annotation][dictionary][facets]") {
    require_each(kFaceted, {{"relief: raised", "relief: raisd", 42, 15,
                             "concept 'dome': unknown relief 'raisd'; did you mean 'raised'?"},
                            {"relief: raised", "relief: convex", 42, 15,
                             "concept 'dome': unknown relief 'convex' (write 'raised' for a word "
                             "true only of a raised detail"}});
    // case matters, as for every other key and value of the format
    require_each(kFaceted,
                 {{"relief: engraved", "relief: Engraved", 38, 15, "did you mean 'engraved'?"},
                  {"relief: raised", "relief: [raised]", 42, 15,
                   "concept 'dome': relief: expected a text, found a list"}});
}

TEST_CASE("check_dictionary: unknown keys in a facet", "[annotation][dictionary][facets]") {
    // the typo is not also reported as a missing 'labels'
    require_each(kFaceted, {{"    labels: {en: outline", "    lables: {en: outline", 9, 5,
                             "unknown key 'lables' in a facet; did you mean 'labels'?"},
                            {"  size:\n", "  size:\n    colour: red\n", 12, 5,
                             "unknown key 'colour' in a facet (known keys: labels, features)"},
                            {"facets:", "facet:", 7, 1,
                             "unknown key 'facet' at the top level; did you mean 'facets'?"},
                            {"  surface:\n", "  my surface:\n", 14, 3,
                             "facet id 'my surface' may hold only letters"}});
}

TEST_CASE("parse_dictionary: a facet entry without concepts is a warning",
          "[annotation][dictionary][facets]") {
    const Dictionary d =
        parse_dictionary(edit(kFaceted, "[area_rel, area]", "[area_rel, area, depth_mean]"), "t");
    REQUIRE(d.warnings.size() == 1);
    CHECK(d.warnings[0].line == 13);
    CHECK(d.warnings[0].column == 32);
    CHECK(d.warnings[0].message ==
          "facet 'size' lists 'depth_mean', which has no concepts: it adds nothing to the facet");
    // it stays listed, but no concept maps to the facet through it
    CHECK(d.facets[1].features.back() == column_of("depth_mean"));
    CHECK(d.feature_facet[static_cast<size_t>(column_of("depth_mean"))] == -1);
}
