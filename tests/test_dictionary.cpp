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
#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "tests/dictionary_fixtures.hpp"

using namespace geotex;
using namespace geotex::test;

// ---- clean dictionaries -------------------------------------------------------------------

TEST_CASE("check_dictionary: a clean dictionary has no problem", "[annotation][dictionary]") {
    const auto problems = check_dictionary(kClean);
    INFO(listing(problems));
    CHECK(problems.empty());
}

TEST_CASE("parse_dictionary: scheme, concepts sorted by column then lower bound, places",
          "[annotation][dictionary]") {
    const Dictionary d = parse_dictionary(kClean, "test.yaml");
    CHECK(d.id == "test");
    CHECK(d.version == "1");
    CHECK(d.namespace_iri == "https://example.org/dict/");
    CHECK(d.languages == std::vector<std::string>{"en", "fr"});
    CHECK(d.titles == std::map<std::string, std::string>{{"en", "Test"}, {"fr", "Essai"}});
    CHECK(d.source_name == "test.yaml");
    CHECK(d.sha256 == sha256_hex(kClean));
    REQUIRE(d.concepts.size() == 3);

    // contour_sphericity is column 1, area column 4
    const DictionaryConcept& circular = d.concepts[0];
    CHECK(circular.id == "circular-shape");
    CHECK(circular.feature == column_of("contour_sphericity"));
    CHECK(circular.lower == 0);
    CHECK(circular.upper == 0.05);
    CHECK(circular.lower_text == "0");
    CHECK(circular.upper_text == "0.05");
    CHECK(circular.labels ==
          std::map<std::string, std::string>{{"en", "circular shape"}, {"fr", "forme circulaire"}});
    CHECK(circular.definitions.empty());
    CHECK(circular.source.empty());
    CHECK(circular.line == 18);
    CHECK(circular.column == 7);

    const DictionaryConcept& non_circular = d.concepts[1];
    CHECK(non_circular.id == "non-circular-shape");
    CHECK(non_circular.lower_text == "0.15");
    CHECK(non_circular.upper == std::numeric_limits<double>::infinity());
    CHECK(non_circular.upper_text.empty());
    CHECK(non_circular.definitions.at("en") == "The contour moves away from a circle.");
    CHECK(non_circular.source == "Table 3");
    CHECK(non_circular.line == 13);

    const DictionaryConcept& small = d.concepts[2];
    CHECK(small.id == "small-area");
    CHECK(small.feature == column_of("area"));
    CHECK(small.lower == -std::numeric_limits<double>::infinity());
    CHECK(small.lower_text.empty());
    CHECK(small.upper_text == "0.1");
    CHECK(small.line == 9);
}

TEST_CASE("parse_dictionary: bounds kept as written, in xsd:decimal form",
          "[annotation][dictionary]") {
    struct Case {
        const char* written;
        const char* text;
        double value;
    };
    // each written form as the upper bound of [-.inf, x]
    const Case cases[] = {
        {"0.05", "0.05", 0.05},      {"-200", "-200", -200}, {"-2E+2", "-200", -200},
        {"+50.0", "50", 50},         {".5", "0.5", 0.5},     {"200.", "200", 200},
        {"1.50e-2", "0.015", 0.015}, {"1e3", "1000", 1000},  {"0.00100e-2", "0.00001", 1e-5},
        {"-0.50e2", "-50", -50},     {"007", "7", 7},        {"12.5e-1", "1.25", 1.25},
    };
    for (const Case& c : cases) {
        const std::string text =
            edit(kClean, "[-.inf, 0.1]", std::string("[-.inf, ") + c.written + "]");
        const Dictionary d = parse_dictionary(text, "t");
        INFO(c.written);
        CHECK(d.concepts[2].upper_text == c.text);
        CHECK(d.concepts[2].upper == c.value);
    }
    // "-0" is 0, and infinities in every YAML spelling
    const Dictionary zero = parse_dictionary(edit(kClean, "[0, 0.05]", "[-0, 0.05]"), "t");
    CHECK(zero.concepts[0].lower_text == "0");
    for (const char* inf : {".inf", ".Inf", ".INF", "+.inf"}) {
        const Dictionary d =
            parse_dictionary(edit(kClean, "[0.15, .inf]", std::string("[0.15, ") + inf + "]"), "t");
        CHECK(d.concepts[1].upper == std::numeric_limits<double>::infinity());
        CHECK(d.concepts[1].upper_text.empty());
    }
}

TEST_CASE("parse_dictionary: byte order mark, comments and flow style are fine",
          "[annotation][dictionary]") {
    CHECK(check_dictionary("\xEF\xBB\xBF" + kClean).empty());
    CHECK(check_dictionary("# a comment\n" + kClean + "# the end\n").empty());
    const std::string flow =
        "{scheme: {id: f, version: v1, namespace: 'urn:example:f/', languages: [en],"
        " title: {en: Flow}},\n"
        " features: {depth_mean: [{id: low, interval: [0, 0.3], labels: {en: low}}]}}\n";
    const auto problems = check_dictionary(flow);
    INFO(listing(problems));
    CHECK(problems.empty());
}

// ---- Dictionary::find ---------------------------------------------------------------------

TEST_CASE("Dictionary::find: lower bound inclusive, upper exclusive, infinities, gaps",
          "[annotation][dictionary]") {
    const Dictionary d = parse_dictionary(kClean, "t");
    const int sphericity = column_of("contour_sphericity");
    const int area = column_of("area");
    const auto id = [&](int feature, double v) {
        const DictionaryConcept* c = d.find(feature, v);
        return c ? c->id : std::string("none");
    };
    const double inf = std::numeric_limits<double>::infinity();
    CHECK(id(sphericity, 0) == "circular-shape");  // lower bound belongs to the interval
    CHECK(id(sphericity, std::nextafter(0.05, 0.0)) == "circular-shape");
    CHECK(id(sphericity, 0.05) == "none");  // upper bound does not; [0.05, 0.15) is a gap
    CHECK(id(sphericity, 0.1) == "none");
    CHECK(id(sphericity, std::nextafter(0.15, 0.0)) == "none");
    CHECK(id(sphericity, 0.15) == "non-circular-shape");
    CHECK(id(sphericity, 1e300) == "non-circular-shape");
    CHECK(id(sphericity, inf) == "none");  // [0.15, .inf) does not hold +inf itself
    CHECK(id(sphericity, -1e-300) == "none");
    CHECK(id(area, -inf) == "small-area");  // [-.inf, 0.1) holds -inf: lower bound inclusive
    CHECK(id(area, -1e300) == "small-area");
    CHECK(id(area, std::nextafter(0.1, 0.0)) == "small-area");
    CHECK(id(area, 0.1) == "none");
    CHECK(id(area, std::nan("")) == "none");
    CHECK(id(column_of("pca_variance_1"), 0.5) == "none");  // feature without concepts
    CHECK(id(-1, 0.0) == "none");
    CHECK(id(kNumFeatures, 0.0) == "none");
}

// ---- one problem at a time, with its place ------------------------------------------------

TEST_CASE("check_dictionary: YAML syntax error at yaml-cpp's place, 1-based",
          "[annotation][dictionary]") {
    // a tab in indentation: yaml-cpp stops at the start of that line
    require_one(edit(kClean, "  version: \"1\"\n", "\tversion: \"1\"\n"), 3, 1,
                "YAML syntax error: illegal tab");
    // an unclosed flow list: yaml-cpp reads on and stops at the ':' of the next key (line 11)
    require_one(edit(kClean, "[-.inf, 0.1]", "[-.inf, 0.1"), 11, 13,
                "YAML syntax error: end of sequence flow not found");
}

TEST_CASE("check_dictionary: duplicate keys, which yaml-cpp lets through",
          "[annotation][dictionary]") {
    require_one(edit(kClean, "      labels: {en: small area, fr: petite aire}\n",
                     "      labels: {en: small area, fr: petite aire}\n"
                     "      labels: {en: tiny area, fr: toute petite aire}\n"),
                12, 7, "duplicate key 'labels' (first at line 11)");
    // the same feature twice
    const std::string twice = kClean +
                              "  area:\n    - id: other\n      interval: [1, 2]\n"
                              "      labels: {en: a, fr: b}\n";
    require_one(twice, 21, 3, "duplicate key 'area' (first at line 8)");
    // inside a flow map
    require_one(edit(kClean, "{en: Test, fr: Essai}", "{en: Test, fr: Essai, fr: E2}"), 6, 32,
                "duplicate key 'fr' (first at line 6)");
}

TEST_CASE("check_dictionary: a quote never closed at the end of the file",
          "[annotation][dictionary]") {
    // yaml-cpp accepts it and makes the rest of the file the text; the quote is at column 15
    require_one(kClean + "      source: \"Table 3", 21, 15, "quoted text is never closed");
    require_one(kClean + "      source: 'Table 3\n", 21, 15, "quoted text is never closed");
    // opened earlier: the rest of the file is swallowed, still reported at the opening quote
    require_one(edit(kClean, "source: Table 3", "source: \"Table 3"), 17, 15,
                "quoted text is never closed");
    // escaped quotes do not close it; a properly closed one with escapes is fine
    require_one(kClean + "      source: \"Table \\\" 3", 21, 15, "never closed");
    CHECK(check_dictionary(kClean + "      source: \"Table \\\"3\\\"\"\n").empty());
    CHECK(check_dictionary(kClean + "      source: 'Table ''3'''\n").empty());
    // apostrophes in plain text and quotes in comments or block texts open nothing
    const std::string text = kClean +
                             "      definition:\n"           // 21
                             "        en: |\n"               // 22
                             "          \"not a quote\n"     // 23
                             "        fr: l'objet # it's\n"  // 24
                             "      source: 'Table 3\n";     // 25
    require_one(text, 25, 15, "quoted text is never closed");
}

TEST_CASE("check_dictionary: unknown keys, with the closest known one",
          "[annotation][dictionary]") {
    // the typo is not also reported as a missing 'labels'
    require_one(edit(kClean, "      labels: {en: small area", "      lables: {en: small area"), 11,
                7, "unknown key 'lables' in a concept; did you mean 'labels'?");
    require_each(
        kClean,
        {{"      source: Table 3", "      sorce: Table 3", 17, 7, "did you mean 'source'?"},
         {"  title:", "  titel:", 6, 3, "unknown key 'titel' in 'scheme'; did you mean 'title'?"},
         {"features:", "feature:", 7, 1,
          "unknown key 'feature' at the top level; did you mean 'features'?"}});
    // nothing close: the known keys are listed (and 'colour' is not mistaken for anything)
    require_one(edit(kClean, "      source: Table 3", "      colour: red"), 17, 7,
                "unknown key 'colour' in a concept (known keys: id, interval, labels, "
                "definition, source, relief, exactMatch, closeMatch)");
}

TEST_CASE("check_dictionary: unknown feature ids, with the closest id",
          "[annotation][dictionary]") {
    require_one(edit(kClean, "  contour_sphericity:", "  contour_sphericty:"), 12, 3,
                "unknown feature 'contour_sphericty'; did you mean 'contour_sphericity'?");
    // the paper's name for the curvedness
    require_each(
        kClean, {{"  area:", "  curvature_index_mean:", 8, 3, "did you mean 'curvedness_mean'?"},
                 {"  area:", "  colour:", 8, 3,
                  "unknown feature 'colour' (the 20 feature ids are listed in docs/features.md)"}});
}

TEST_CASE("check_dictionary: bounds that are not numbers", "[annotation][dictionary]") {
    // line 19 is "      interval: [0, 0.05]": '[' at 17, lower at 18, upper at 21
    require_each(kClean,
                 {{"[0, 0.05]", "[0, abc]", 19, 21,
                   "concept 'circular-shape': upper bound 'abc' is not a number"},
                  {"[0, 0.05]", "[zero, 0.05]", 19, 18, "lower bound 'zero'"},
                  {"[0, 0.05]", "[0, inf]", 19, 21, "writes infinity as .inf or -.inf"},
                  {"[0, 0.05]", "[0, \"0.05\"]", 19, 21, "upper bound '0.05' is written as text"},
                  {"[0, 0.05]", "[0, .nan]", 19, 21, "is not a number"},
                  {"[0, 0.05]", "[0, 0x10]", 19, 21, "is not a number"},
                  {"[0, 0.05]", "[0, 1e400]", 19, 21, "out of the range of a double"},
                  {"[0, 0.05]", "[0, ~]", 19, 21, "found nothing"},
                  {"[0, 0.05]", "[0, [1]]", 19, 21, "found a list"}});
}

TEST_CASE("check_dictionary: a bound holds at most 15 significant digits",
          "[annotation][dictionary]") {
    // 0.15 followed by 52 zeros and a 1 (55 digits) is above 0.15 as a decimal, so it would
    // overlap the neighbour [0.15, .inf); as doubles the two are equal and touch.
    const std::string long_bound = "0.15" + std::string(52, '0') + "1";
    CHECK(std::stod(long_bound) == 0.15);  // why the doubles alone cannot see the overlap
    require_one(
        edit(kClean, "[0, 0.05]", "[0, " + long_bound + "]"), 19, 21,
        "upper bound '" + long_bound + "' has 55 significant digits; a bound has at most 15");
    // 15 digits pass, whatever the zeros around them; 16 do not
    CHECK(check_dictionary(edit(kClean, "[0, 0.05]", "[0, 0.0123456789012345000]")).empty());
    CHECK(check_dictionary(edit(kClean, "[0, 0.05]", "[0, 12345678901234.5e-15]")).empty());
    require_each(kClean,
                 {{"[0, 0.05]", "[0, 0.01234567890123456]", 19, 21, "has 16 significant digits"},
                  {"[0, 0.05]", "[1e-310, 0.05]", 19, 18, "below the smallest normal double"}});
}

TEST_CASE("check_dictionary: lower bound not below the upper one", "[annotation][dictionary]") {
    require_each(
        kClean,
        {{"[0, 0.05]", "[0.05, 0]", 19, 17,
          "interval [0.05, 0) is empty: the lower bound must be below the upper bound"},
         {"[0, 0.05]", "[0.1, 0.10]", 19, 17, "interval [0.1, 0.1) is empty"},
         {"[0, 0.05]", "[.inf, .inf]", 19, 17, "is empty"},
         {"[0, 0.05]", "[0, -.inf]", 19, 17, "is empty"},
         {"[0, 0.05]", "[0, 1, 2]", 19, 17, "interval has 3 values; expected [lower, upper]"}});
}

TEST_CASE("check_dictionary: overlapping intervals of one feature name both concepts",
          "[annotation][dictionary]") {
    // reported at the later concept of the file, naming the other and its line
    require_one(edit(kClean, "[0, 0.05]", "[0, 0.2]"), 19, 17,
                "interval [0, 0.2) of 'circular-shape' overlaps [0.15, .inf) of "
                "'non-circular-shape' (line 13)");
    // touching intervals do not overlap
    CHECK(check_dictionary(edit(kClean, "[0, 0.05]", "[0, 0.15]")).empty());
    // the same interval on another feature is no overlap
    CHECK(check_dictionary(edit(kClean, "[-.inf, 0.1]", "[0, 0.05]")).empty());
}

TEST_CASE("check_dictionary: a label missing in a required language", "[annotation][dictionary]") {
    require_one(edit(kClean, "{en: small area, fr: petite aire}", "{en: small area}"), 11, 15,
                "concept 'small-area': labels: no text in 'fr'");
    // extra languages are welcome
    CHECK(check_dictionary(edit(kClean, "fr: petite aire}", "fr: petite aire, de: kleine Fläche}"))
              .empty());
    // the title too
    require_one(edit(kClean, "{en: Test, fr: Essai}", "{fr: Essai}"), 6, 10,
                "scheme.title: no text in 'en'");
    // an empty label, a control character in a label
    require_each(kClean, {{"fr: petite aire}", "fr: \"\"}", 11, 36, "is empty"},
                          {"fr: petite aire}", "fr: \"petite\\taire\"}", 11, 36,
                           "control character U+0009"}});
}

TEST_CASE("check_dictionary: duplicate concept ids name the first one's line",
          "[annotation][dictionary]") {
    require_one(edit(kClean, "id: circular-shape", "id: small-area"), 18, 11,
                "duplicate concept id 'small-area' (first at line 9)");
}

TEST_CASE("check_dictionary: missing required keys", "[annotation][dictionary]") {
    require_each(kClean, {{"      interval: [-.inf, 0.1]\n", "", 9, 7,
                           "concept 'small-area': missing required key 'interval'"},
                          {"    - id: small-area\n      interval", "    - interval", 9, 7,
                           "concept 1 of 'area': missing required key 'id'"},
                          {"  namespace: \"https://example.org/dict/\"\n", "", 2, 3,
                           "scheme: missing required key 'namespace'"}});
    require_one(kClean.substr(0, kClean.find("features:")), 1, 1,
                "the dictionary: missing required key 'features'");
    // without `languages`, labels cannot be checked for languages: one problem only
    require_one(edit(kClean, "  languages: [en, fr]\n", ""), 2, 3,
                "scheme: missing required key 'languages'");
}

TEST_CASE("check_dictionary: values of the wrong kind", "[annotation][dictionary]") {
    require_one(edit(kClean, "labels: {en: small area, fr: petite aire}", "labels: [en, fr]"), 11,
                15, "labels: expected a map from language tag to text");
    require_each(kClean,
                 {{"[-.inf, 0.1]", "0.1", 10, 17,
                   "concept 'small-area': interval: expected [lower, upper], found a single value"},
                  {"  languages: [en, fr]", "  languages: en", 5, 14,
                   "scheme.languages: expected a list of language tags"}});
    // an empty value is reported at its key
    require_one(edit(kClean, "      source: Table 3", "      source:"), 17, 7,
                "source: expected a text, found nothing");
    // a concept list that is a map, a concept that is a text
    require_one(edit(kClean,
                     "  area:\n    - id: small-area\n      interval: [-.inf, 0.1]\n"
                     "      labels: {en: small area, fr: petite aire}\n",
                     "  area: {id: small-area}\n"),
                8, 9, "feature 'area': expected a list of concepts");
    require_one(kClean + "    - circular\n", 21, 7,
                "concept 3 of 'contour_sphericity': expected a map with id, interval and labels");
    require_one("scheme: 5\nfeatures: {area: []}\n", 1, 9, "scheme: expected a map");
}

TEST_CASE("check_dictionary: scheme values", "[annotation][dictionary]") {
    require_each(
        kClean,
        {{"https://example.org/dict/", "https://example.org/dict", 4, 14, "must end in '/' or '#'"},
         {"https://example.org/dict/", "example.org/dict/", 4, 14, "is not an absolute IRI"},
         {"https://example.org/dict/", "https://example.org/my dict/", 4, 14,
          "a character that IRIs forbid at position 23"},
         {"[en, fr]", "[en, \"f r\"]", 5, 19, "'f r' is not a language tag"},
         {"[en, fr]", "[en, fr, en]", 5, 23, "lists 'en' twice"},
         {"[en, fr]", "[]", 5, 14, "scheme.languages is empty"},
         {"  id: test", "  id: my test", 2, 7, "scheme.id 'my test' may hold"},
         {"id: circular-shape", "id: circular shape", 18, 11,
          "concept id 'circular shape' may hold only letters"}});
}

TEST_CASE("parse_dictionary: scheme metadata, creator, licence and date of the version",
          "[annotation][dictionary]") {
    const std::string meta =
        "  title: {en: Test, fr: Essai}\n"
        "  creator: https://w3id.org/geotex/\n"
        "  license: https://creativecommons.org/licenses/by/4.0/\n"
        "  modified: 2024-02-29\n";
    const Dictionary d =
        parse_dictionary(edit(kClean, "  title: {en: Test, fr: Essai}\n", meta), "meta.yaml");
    CHECK(d.creators == std::vector<std::string>{"https://w3id.org/geotex/"});
    CHECK(d.license == "https://creativecommons.org/licenses/by/4.0/");
    CHECK(d.modified == "2024-02-29");
    // A list of creators, in the curator's order; all three keys are optional.
    const Dictionary two = parse_dictionary(
        edit(kClean, "  title: {en: Test, fr: Essai}\n",
             "  title: {en: Test, fr: Essai}\n  creator: [https://b.example/, \"urn:x:a\"]\n"),
        "two.yaml");
    CHECK(two.creators == std::vector<std::string>{"https://b.example/", "urn:x:a"});
    const Dictionary none = parse_dictionary(kClean, "clean.yaml");
    CHECK(none.creators.empty());
    CHECK(none.license.empty());
    CHECK(none.modified.empty());
}

TEST_CASE("check_dictionary: creator, licence and date that RDF cannot carry",
          "[annotation][dictionary]") {
    const auto with = [](const std::string& line) {
        return edit(kClean, "  title: {en: Test, fr: Essai}\n",
                    "  title: {en: Test, fr: Essai}\n" + line + "\n");
    };
    // line 7 holds the new key; values start at column 12 (creator: ), 12 (license: ),
    // 13 (modified: )
    require_one(with("  creator: geotex project"), 7, 12,
                "scheme.creator 'geotex project' is not an absolute IRI");
    require_one(with("  creator: [https://a.example/, https://a.example/]"), 7, 33,
                "scheme.creator lists 'https://a.example/' twice");
    require_one(with("  creator: []"), 7, 12, "scheme.creator is empty");
    require_one(with("  creator: {a: b}"), 7, 12, "scheme.creator: expected an IRI or a list");
    require_one(with("  license: [https://a.example/, https://b.example/]"), 7, 12,
                "scheme.license: expected one IRI");
    require_one(with("  license: https://a.example/x/../y"), 7, 12,
                "has a '..' path segment at position 21");
    require_one(with("  licence: https://a.example/"), 7, 3,
                "unknown key 'licence' in 'scheme'; did you mean 'license'?");
    require_one(with("  modified: 2026-13-01"), 7, 13,
                "scheme.modified '2026-13-01' is not a date");
    require_one(with("  modified: 2023-02-29"), 7, 13, "is not a date");  // not a leap year
    require_one(with("  modified: 1 December 2026"), 7, 13, "write the day this version was made");
    require_one(with("  modified: \"2026-12-01T10:00:00Z\""), 7, 13, "is not a date");
    CHECK(check_dictionary(with("  modified: \"2000-02-29\"")).empty());  // 2000 is a leap year
}

TEST_CASE("parse_dictionary: a concept's matches in other vocabularies, absolute IRIs",
          "[annotation][dictionary]") {
    const std::string aat = "http://vocab.getty.edu/aat/";
    const Dictionary d =
        parse_dictionary(edit(kClean, "      source: Table 3\n",
                              "      source: Table 3\n      exactMatch: " + aat +
                                  "1\n      closeMatch: [" + aat + "2, " + aat + "3]\n"),
                         "match.yaml");
    const DictionaryConcept& c = d.concepts[1];  // contour_sphericity from 0.15
    REQUIRE(c.id == "non-circular-shape");
    CHECK(c.exact_matches == std::vector<std::string>{aat + "1"});
    CHECK(c.close_matches == std::vector<std::string>{aat + "2", aat + "3"});
    CHECK(d.concepts[0].exact_matches.empty());
    // Line 18 holds the key, its value starts at column 19 (exactMatch) or 19 (closeMatch).
    const auto with = [](const std::string& line) {
        return edit(kClean, "      source: Table 3\n", "      source: Table 3\n" + line + "\n");
    };
    require_one(with("      exactMatch: aat:300"), 18, 19,
                "concept 'non-circular-shape': exactMatch 'aat:300' is not an http:// or https:// "
                "IRI");
    require_one(with("      exactMatch: 300000000"), 18, 19, "is not an absolute IRI");
    require_one(with("      closeMatch: [\"http://vocab.getty.edu/aat/1 \"]"), 18, 20,
                "closeMatch 'http://vocab.getty.edu/aat/1 ' contains a character that IRIs forbid");
    require_one(with("      closeMatch: [[http://a.example/]]"), 18, 20,
                "closeMatch: expected an IRI, found a list");
    require_one(with("      exactmatch: http://a.example/"), 18, 7,
                "unknown key 'exactmatch' in a concept; did you mean 'exactMatch'?");
}

TEST_CASE("check_dictionary: bad UTF-8 and characters YAML forbids", "[annotation][dictionary]") {
    // "  title: {en: Test, fr: Ess?i}": the bad byte is the 28th character
    const auto problems = check_dictionary(edit(kClean, "Essai", "Ess\xFFi"));
    INFO(listing(problems));
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].line == 6);
    CHECK(problems[0].column == 28);
    CHECK_THAT(problems[0].message, Catch::Contains("invalid UTF-8 (1 byte from 0xFF)"));
    // a truncated sequence, an overlong form, a surrogate: one problem per run of bad bytes
    require_each(kClean, {{"Essai", "Ess\xC3", 6, 28, "invalid UTF-8"},
                          {"Essai", "Ess\xC0\xAF", 6, 28, "invalid UTF-8 (2 bytes"},
                          {"Essai", "Ess\xED\xA0\x80", 6, 28, "invalid UTF-8 (3 bytes"}});
    require_one(edit(kClean, "Essai", std::string("Ess\x01", 4)), 6, 28, "U+0001 is not allowed");
    require_one(edit(kClean, "Essai", "Ess\xC2\x80"), 6, 28, "U+0080 is not allowed");
}

TEST_CASE("check_dictionary: columns count characters, not bytes", "[annotation][dictionary]") {
    // "été" is 3 characters and 5 bytes: the bad bound is the 66th character (70th byte)
    const std::string text =
        "scheme: {id: a, version: \"1\", namespace: \"urn:x:a/\", languages: [en, fr],"
        " title: {en: A, fr: A}}\n"
        "features:\n"
        "  area:\n"
        "    - {labels: {en: \"été\", fr: \"été\"}, id: summer, interval: [0, x]}\n";
    require_one(text, 4, 66, "upper bound 'x' is not a number");
    // a byte order mark takes no column
    require_one("\xEF\xBB\xBF" + edit(kClean, "scheme:", "schema:"), 1, 1, "unknown key 'schema'");
}

TEST_CASE("check_dictionary: one document, not empty", "[annotation][dictionary]") {
    require_one(kClean + "---\nscheme: {}\n", 21, 1, "a second YAML document");
    CHECK(check_dictionary(kClean + "---\n").empty());  // an empty trailing document is harmless
    require_one("", 1, 1, "empty dictionary");
    require_one("# nothing yet\n", 1, 1, "empty dictionary");
    // yaml-cpp 0.7 starts empty documents at a stray top-level ',' forever: stopped, reported
    require_one(",", 1, 1, "YAML syntax error: the YAML reader cannot get past this point");
    require_one("- a\n- b\n", 1, 1, "the dictionary: expected a map");
    require_one(edit(kClean, kClean.substr(kClean.find("  area:")), "") + "  {}\n", 8, 3,
                "features is empty");
}

// ---- everything at once -------------------------------------------------------------------

TEST_CASE("check_dictionary: every problem at once, sorted by place", "[annotation][dictionary]") {
    std::string text = edit(kClean, "Essai", "Ess\xFFi");                                 // 6:28
    text = edit(text, "      labels: {en: small area", "      lables: {en: small area");  // 11:7
    text = edit(text, "  contour_sphericity:", "  contour_sphericty:");                   // 12:3
    text = edit(text, "      source: Table 3\n",
                "      source: Table 3\n      source: Table 4\n");  // 18:7
    text = edit(text, "[0, 0.05]", "[0, abc]");                     // 20:21
    text = edit(text, "id: circular-shape", "id: small-area");      // 19:11
    const auto problems = check_dictionary(text);
    INFO(listing(problems));
    REQUIRE(problems.size() == 6);
    const std::pair<long, long> places[] = {{6, 28}, {11, 7}, {12, 3}, {18, 7}, {19, 11}, {20, 21}};
    for (size_t i = 0; i < problems.size(); ++i) {
        CHECK(problems[i].line == places[i].first);
        CHECK(problems[i].column == places[i].second);
    }
    CHECK_THAT(problems[0].message, Catch::Contains("UTF-8"));
    CHECK_THAT(problems[1].message, Catch::Contains("lables"));
    CHECK_THAT(problems[2].message, Catch::Contains("contour_sphericty"));
    CHECK_THAT(problems[3].message, Catch::Contains("duplicate key 'source' (first at line 17)"));
    CHECK_THAT(problems[4].message, Catch::Contains("duplicate concept id 'small-area'"));
    CHECK_THAT(problems[5].message, Catch::Contains("'abc' is not a number"));
}

TEST_CASE("parse_dictionary: throws ParseError at the first problem with the count",
          "[annotation][dictionary]") {
    std::string text = edit(kClean, "[0, 0.05]", "[0, abc]");
    text = edit(text, "  title:", "  titel:");
    try {
        parse_dictionary(text, "my.yaml");
        FAIL("no exception");
    } catch (const ParseError& e) {
        CHECK(e.file() == "my.yaml");
        CHECK(e.line() == 6);
        CHECK(e.column() == 3);
        CHECK_THAT(std::string(e.what()), Catch::Contains("unknown key 'titel'"));
        CHECK_THAT(std::string(e.what()), Catch::Contains("and 1 more problem;"));
    }
    REQUIRE_THROWS_AS(parse_dictionary("", "empty.yaml"), ParseError);
}
