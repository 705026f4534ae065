// The texture label: one rule for the console, the JSON report and rdfs:label.

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "annotation/texture_label.hpp"
#include "common/errors.hpp"

using namespace geotex;

namespace {

DictionaryConcept concept_of(const std::string& id, std::map<std::string, std::string> labels) {
    DictionaryConcept c;
    c.id = id;
    c.labels = std::move(labels);
    return c;
}

// Declared French first: the first language of the dictionary is not the first in sort order.
Dictionary french_first() {
    Dictionary d;
    d.languages = {"fr", "en"};
    return d;
}

}  // namespace

TEST_CASE("concepts_label: the requested language when every concept has it",
          "[annotation][label]") {
    const Dictionary d = french_first();
    const auto a = concept_of("round", {{"en", "round"}, {"fr", "rond"}});
    const auto b = concept_of("small", {{"en", "small"}, {"fr", "petit"}});
    const Label en = concepts_label({&a, &b}, d, "en");
    CHECK(en.text == "round, small");
    CHECK(en.language == "en");
    const Label fr = concepts_label({&a, &b}, d, "fr");
    CHECK(fr.text == "rond, petit");
    CHECK(fr.language == "fr");
    CHECK(concepts_label({&b}, d, "en").text == "small");
}

TEST_CASE("concepts_label: a language the dictionary lacks falls back to its first language",
          "[annotation][label]") {
    const Dictionary d = french_first();
    const auto a = concept_of("round", {{"en", "round"}, {"fr", "rond"}});
    const auto b = concept_of("small", {{"en", "small"}, {"fr", "petit"}});
    // "de" is absent: the dictionary's first language (fr), not the first in sort order (en).
    const Label de = concepts_label({&a, &b}, d, "de");
    CHECK(de.text == "rond, petit");
    CHECK(de.language == "fr");
    // A single concept follows the same rule.
    CHECK(concepts_label({&a}, d, "de").language == "fr");
}

TEST_CASE("concepts_label: one language for all, or each its own first label without one",
          "[annotation][label]") {
    Dictionary d = french_first();
    const auto a = concept_of("round", {{"en", "round"}, {"fr", "rond"}});
    const auto b = concept_of("small", {{"en", "small"}});  // no French label
    const Label mixed = concepts_label({&a, &b}, d, "fr");
    CHECK(mixed.text == "round, small");  // never "rond, small": one language for the label
    CHECK(mixed.language == "en");
    // No language of the dictionary: the first concept's languages are tried.
    d.languages.clear();
    const auto c = concept_of("deep", {{"de", "tief"}, {"it", "profondo"}});
    const auto e = concept_of("wide", {{"it", "largo"}});
    const Label it = concepts_label({&c, &e}, d, "fr");
    CHECK(it.text == "profondo, largo");
    CHECK(it.language == "it");
    // Nothing in common: each concept's first label, its id when it has none, untagged.
    const auto f = concept_of("bare", {});
    const Label none = concepts_label({&a, &e, &f}, d, "fr");
    CHECK(none.text == "round, largo, bare");
    CHECK(none.language.empty());
    CHECK(concepts_label({}, d, "fr").text.empty());
}

TEST_CASE("texture_label: the chosen or withheld concepts of a texture", "[annotation][label]") {
    const Dictionary d = french_first();
    const auto a = concept_of("round", {{"en", "round"}, {"fr", "rond"}});
    const auto b = concept_of("small", {{"en", "small"}, {"fr", "petit"}});
    TextureDescription t;
    t.texture = 4;
    t.features.resize(3);
    t.features[0].concept_ptr = &b;
    t.features[2].concept_ptr = &a;
    t.chosen = {2, 0};
    t.withheld = {0};
    CHECK(texture_label(t, t.chosen, d, "en").text == "round, small");
    CHECK(texture_label(t, t.withheld, d, "fr").text == "petit");
    CHECK(texture_label(t, {}, d, "fr").text.empty());
    CHECK_THROWS_AS(texture_label(t, {1}, d, "en"), InvalidInput);  // no concept
    CHECK_THROWS_AS(texture_label(t, {3}, d, "en"), InvalidInput);
    CHECK_THROWS_AS(texture_label(t, {-1}, d, "en"), InvalidInput);
}
