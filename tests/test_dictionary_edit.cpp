#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/dictionary_edit.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "tests/dictionary_fixtures.hpp"

using namespace geotex;
using namespace geotex::test;

namespace {

// A dictionary written as curators do: comments, a quoted version, flow and block maps, a
// shared bound (0.05) and a gap (0.15 starts after a gap from 0.1).
const std::string kText =
    "# my dictionary\n"                                                        //  1
    "scheme:\n"                                                                //  2
    "  id: test   # the id\n"                                                  //  3
    "  version: \"1.9\"\n"                                                     //  4
    "  namespace: \"https://example.org/dict/\"\n"                             //  5
    "  languages: [en, fr]\n"                                                  //  6
    "  title: {en: Test, fr: Essai}\n"                                         //  7
    "  modified: 2026-01-02\n"                                                 //  8
    "features:\n"                                                              //  9
    "  contour_sphericity:\n"                                                  // 10
    "    - id: circular-shape\n"                                               // 11
    "      interval: [0, 0.05]   # Table 3\n"                                  // 12
    "      labels: {en: circular shape, fr: forme circulaire}\n"               // 13
    "    - id: close-to-circular-shape\n"                                      // 14
    "      interval: [5e-2, 0.1]\n"                                            // 15
    "      labels:\n"                                                          // 16
    "        en: close to circular shape\n"                                    // 17
    "        fr: 'forme presque circulaire'\n"                                 // 18
    "    - id: non-circular-shape\n"                                           // 19
    "      interval: [0.15, .inf]\n"                                           // 20
    "      labels: {en: \"non circular shape\", fr: forme non circulaire}\n";  // 21

DictionaryEdit bound(const std::string& id, bool upper, const std::string& value) {
    DictionaryEdit e;
    e.kind = DictionaryEdit::Kind::Bound;
    e.concept_id = id;
    e.upper = upper;
    e.value = value;
    return e;
}

DictionaryEdit label(const std::string& id, const std::string& language, const std::string& value) {
    DictionaryEdit e;
    e.kind = DictionaryEdit::Kind::Label;
    e.concept_id = id;
    e.language = language;
    e.value = value;
    return e;
}

const DictionaryConcept& concept_of(const Dictionary& d, const std::string& id) {
    for (const auto& c : d.concepts)
        if (c.id == id) return c;
    FAIL("no concept " << id);
    return d.concepts.front();
}

std::string crlf(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '\n') out += '\r';
        out += c;
    }
    return out;
}

}  // namespace

TEST_CASE("edit_dictionary: the fixture is clean", "[annotation][dictionary_edit]") {
    INFO(listing(check_dictionary(kText)));
    REQUIRE(check_dictionary(kText).empty());
}

TEST_CASE("edit_dictionary: a shared bound moves both intervals, nothing else changes",
          "[annotation][dictionary_edit]") {
    const auto r = edit_dictionary(kText, {bound("circular-shape", true, "0.07")});
    INFO(listing(r.problems));
    CHECK(r.problems.empty());
    // 0.05 and 5e-2 are one number: both are rewritten, the comment after the first stays
    const std::string expected =
        edit(edit(kText, "[0, 0.05]", "[0, 0.07]"), "[5e-2, 0.1]", "[0.07, 0.1]");
    CHECK(r.text == expected);
    const Dictionary d = parse_dictionary(r.text, "t.yaml");
    CHECK(concept_of(d, "circular-shape").upper == 0.07);
    CHECK(concept_of(d, "close-to-circular-shape").lower == 0.07);
    CHECK(concept_of(d, "close-to-circular-shape").upper == 0.1);
}

TEST_CASE("edit_dictionary: a bound next to a gap moves alone", "[annotation][dictionary_edit]") {
    const auto r = edit_dictionary(kText, {bound("non-circular-shape", false, "0.12")});
    CHECK(r.problems.empty());
    CHECK(r.text == edit(kText, "[0.15, .inf]", "[0.12, .inf]"));
    const Dictionary d = parse_dictionary(r.text, "t.yaml");
    CHECK(concept_of(d, "non-circular-shape").lower == 0.12);
    CHECK(concept_of(d, "close-to-circular-shape").upper == 0.1);
}

TEST_CASE("edit_dictionary: the lower bound of the next interval moves its neighbour's upper",
          "[annotation][dictionary_edit]") {
    const auto r = edit_dictionary(kText, {bound("close-to-circular-shape", false, "0.04")});
    CHECK(r.problems.empty());
    CHECK(r.text == edit(edit(kText, "[0, 0.05]", "[0, 0.04]"), "[5e-2, 0.1]", "[0.04, 0.1]"));
}

TEST_CASE("edit_dictionary: successive edits of one bound keep the last, still shared",
          "[annotation][dictionary_edit]") {
    const auto r = edit_dictionary(kText, {bound("circular-shape", true, "0.07"),
                                           bound("close-to-circular-shape", false, "0.08"),
                                           bound("non-circular-shape", true, "1e3")});
    INFO(listing(r.problems));
    CHECK(r.problems.empty());
    CHECK(r.text == edit(edit(edit(kText, "[0, 0.05]", "[0, 0.08]"), "[5e-2, 0.1]", "[0.08, 0.1]"),
                         "[0.15, .inf]", "[0.15, 1e3]"));
}

TEST_CASE("edit_dictionary: an overlap or an inverted interval is check_dictionary's problem",
          "[annotation][dictionary_edit]") {
    SECTION("overlap") {
        // 0.12 is beyond the gap: close-to-circular [0.05, 0.1) stays, non-circular moves down
        const auto r = edit_dictionary(kText, {bound("non-circular-shape", false, "0.09")});
        REQUIRE(r.problems.size() == 1);
        CHECK(r.problems[0].line == 20);
        CHECK(r.problems[0].column == 17);
        CHECK(r.problems[0].message.find("overlaps") != std::string::npos);
    }
    SECTION("inverted") {
        const auto r = edit_dictionary(kText, {bound("non-circular-shape", true, "0.1")});
        REQUIRE(r.problems.size() == 1);
        CHECK(r.problems[0].line == 20);
        CHECK(r.problems[0].message.find("is empty") != std::string::npos);
    }
}

TEST_CASE("edit_dictionary: bad edits are problems, the good ones apply",
          "[annotation][dictionary_edit]") {
    const auto r = edit_dictionary(
        kText, {bound("no-such-concept", true, "0.2"), bound("circular-shape", true, "0,07"),
                bound("circular-shape", false, "\"0\""), label("circular-shape", "e n", "x"),
                bound("non-circular-shape", false, "0.12")});
    REQUIRE(r.problems.size() == 4);
    CHECK(r.problems[0].line == 0);
    CHECK(r.problems[0].message == "edit 1: unknown concept 'no-such-concept'");
    CHECK(r.problems[1].line == 12);
    CHECK(r.problems[1].message.find("edit 2: upper bound '0,07'") == 0);
    CHECK(r.problems[1].message.find("is not a number") != std::string::npos);
    CHECK(r.problems[2].message.find("edit 3: lower bound") == 0);
    CHECK(r.problems[3].message.find("edit 4: label language 'e n'") == 0);
    CHECK(r.text == edit(kText, "[0.15, .inf]", "[0.12, .inf]"));
}

TEST_CASE("edit_dictionary: labels keep their quoting, and are quoted when YAML needs it",
          "[annotation][dictionary_edit]") {
    SECTION("plain in a flow map") {
        const auto r = edit_dictionary(kText, {label("circular-shape", "en", "round shape")});
        CHECK(r.problems.empty());
        CHECK(r.text == edit(kText, "{en: circular shape,", "{en: round shape,"));
    }
    SECTION("a comma in a flow map needs quotes") {
        const auto r = edit_dictionary(kText, {label("circular-shape", "en", "round, even")});
        CHECK(r.problems.empty());
        CHECK(r.text == edit(kText, "{en: circular shape,", "{en: \"round, even\","));
        CHECK(concept_of(parse_dictionary(r.text, "t"), "circular-shape").labels.at("en") ==
              "round, even");
    }
    SECTION("single quotes stay single, a quote inside doubled") {
        const auto r =
            edit_dictionary(kText, {label("close-to-circular-shape", "fr", "forme d'un cercle")});
        CHECK(r.problems.empty());
        CHECK(r.text == edit(kText, "fr: 'forme presque circulaire'", "fr: 'forme d''un cercle'"));
        CHECK(
            concept_of(parse_dictionary(r.text, "t"), "close-to-circular-shape").labels.at("fr") ==
            "forme d'un cercle");
    }
    SECTION("double quotes stay double, escapes where needed") {
        const auto r = edit_dictionary(kText, {label("non-circular-shape", "en", "a \"b\" c")});
        CHECK(r.problems.empty());
        CHECK(r.text == edit(kText, "\"non circular shape\"", "\"a \\\"b\\\" c\""));
        CHECK(concept_of(parse_dictionary(r.text, "t"), "non-circular-shape").labels.at("en") ==
              "a \"b\" c");
    }
    SECTION("a word YAML reads as another type is quoted") {
        const auto r = edit_dictionary(kText, {label("close-to-circular-shape", "en", "yes")});
        CHECK(r.text == edit(kText, "en: close to circular shape", "en: \"yes\""));
    }
    SECTION("a new language in a flow map and in a block map") {
        const auto r =
            edit_dictionary(kText, {label("circular-shape", "de", "kreisförmig"),
                                    label("close-to-circular-shape", "de", "fast rund"),
                                    label("close-to-circular-shape", "de", "beinahe rund")});
        INFO(listing(r.problems));
        CHECK(r.problems.empty());
        CHECK(r.text ==
              edit(edit(kText, "fr: forme circulaire}", "fr: forme circulaire, de: kreisförmig}"),
                   "        fr: 'forme presque circulaire'\n",
                   "        fr: 'forme presque circulaire'\n        de: beinahe rund\n"));
        const Dictionary d = parse_dictionary(r.text, "t");
        CHECK(concept_of(d, "circular-shape").labels.at("de") == "kreisförmig");
        CHECK(concept_of(d, "close-to-circular-shape").labels.at("de") == "beinahe rund");
    }
    SECTION("a label another concept has is check_dictionary's problem at its place") {
        const auto r =
            edit_dictionary(kText, {label("circular-shape", "en", "Non circular shape")});
        REQUIRE(r.problems.size() == 1);
        CHECK(r.problems[0].line == 21);
    }
}

TEST_CASE("edit_dictionary: CRLF line ends and a byte order mark are kept",
          "[annotation][dictionary_edit]") {
    const std::string text = "\xEF\xBB\xBF" + crlf(kText);
    const auto r = edit_dictionary(text, {bound("circular-shape", true, "0.07"),
                                          label("close-to-circular-shape", "de", "fast rund")});
    INFO(listing(r.problems));
    CHECK(r.problems.empty());
    const std::string expected =
        "\xEF\xBB\xBF" +
        crlf(edit(edit(edit(kText, "[0, 0.05]", "[0, 0.07]"), "[5e-2, 0.1]", "[0.07, 0.1]"),
                  "        fr: 'forme presque circulaire'\n",
                  "        fr: 'forme presque circulaire'\n        de: fast rund\n"));
    CHECK(r.text == expected);
}

TEST_CASE("edit_dictionary: a text that is not YAML is returned with its problems",
          "[annotation][dictionary_edit]") {
    const std::string broken = kText + "  area: [\n";
    const auto r = edit_dictionary(broken, {bound("circular-shape", true, "0.07")});
    CHECK(r.text == broken);
    CHECK(!r.problems.empty());
}

TEST_CASE("next_version: the last number goes up by one", "[annotation][dictionary_edit]") {
    CHECK(next_version("2.0") == "2.1");
    CHECK(next_version("2.9") == "2.10");
    CHECK(next_version("1.99") == "1.100");
    CHECK(next_version("v7") == "v8");
    CHECK(next_version("2.0-beta3") == "2.0-beta4");
    CHECK(next_version("2.0-rc") == "2.1-rc");
    CHECK(next_version("draft") == "draft.1");
}

TEST_CASE("stamp_new_version: version and modified change, nothing else",
          "[annotation][dictionary_edit]") {
    SECTION("both present") {
        const std::string out = stamp_new_version(kText, "2026-12-02");
        CHECK(out == edit(edit(kText, "version: \"1.9\"", "version: \"1.10\""),
                          "modified: 2026-01-02", "modified: 2026-12-02"));
        const Dictionary d = parse_dictionary(out, "t");
        CHECK(d.version == "1.10");
        CHECK(d.modified == "2026-12-02");
    }
    SECTION("modified absent: added under version") {
        const std::string text = edit(kText, "  modified: 2026-01-02\n", "");
        const std::string out = stamp_new_version(crlf(text), "2026-12-02");
        CHECK(out == crlf(edit(text, "  version: \"1.9\"\n",
                               "  version: \"1.10\"\n  modified: 2026-12-02\n")));
        CHECK(parse_dictionary(out, "t").modified == "2026-12-02");
    }
    SECTION("preconditions") {
        CHECK_THROWS_AS(stamp_new_version(kText, "2026-02-30"), InvalidInput);
        CHECK_THROWS_AS(stamp_new_version("features: {}\n", "2026-12-02"), InvalidInput);
    }
}

TEST_CASE("edit_dictionary: the default dictionary, a shared bound and a French label",
          "[annotation][dictionary_edit]") {
    const std::string text = read_source_file("dictionaries/default.yaml");
    const auto r =
        edit_dictionary(text, {bound("ridge", true, "0.6"), label("dome", "fr", "dôme arrondi")});
    INFO(listing(r.problems));
    CHECK(r.problems.empty());
    CHECK(r.text == edit(edit(edit(text, "interval: [0.375, 0.625]", "interval: [0.375, 0.6]"),
                              "interval: [0.625, 0.875]", "interval: [0.6, 0.875]"),
                         "{en: dome, fr: dôme}", "{en: dome, fr: dôme arrondi}"));
    const Dictionary d = parse_dictionary(r.text, "default.yaml");
    CHECK(concept_of(d, "dome").lower == 0.6);
    CHECK(concept_of(d, "dome").labels.at("fr") == "dôme arrondi");
    CHECK(concept_of(d, "ridge").upper == 0.6);
    const std::string stamped = stamp_new_version(r.text, "2026-12-02");
    CHECK(stamped == edit(edit(r.text, "  version: \"2.0\"", "  version: \"2.1\""),
                          "  modified: 2026-12-01   #", "  modified: 2026-12-02   #"));
}

TEST_CASE("edit_dictionary: bounds written as a block list, with comments",
          "[annotation][dictionary_edit]") {
    const std::string text = edit(kText, "      interval: [0, 0.05]   # Table 3\n",
                                  "      interval:\n        - 0\n        - 0.05  # Table 3\n");
    REQUIRE(check_dictionary(text).empty());
    const auto r = edit_dictionary(text, {bound("circular-shape", true, "0.07")});
    INFO(listing(r.problems));
    CHECK(r.problems.empty());
    CHECK(r.text == edit(edit(text, "        - 0.05  # Table 3\n", "        - 0.07  # Table 3\n"),
                         "[5e-2, 0.1]", "[0.07, 0.1]"));
}
