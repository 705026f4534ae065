// Tests of the SPARQL result writers (ontology/query_result_writer.cpp): CSV (RFC 4180),
// SPARQL 1.1 results JSON and the aligned table.

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "tests/sparql_test_support.hpp"

using namespace geotex::sparql_test;

// ---- output formats -------------------------------------------------------------------

TEST_CASE("write_query_result: CSV quotes commas, quotes and line breaks (RFC 4180)",
          "[ontology][sparql]") {
    const QueryResult r = run_sparql(query_file("texture-labels.rq"), {kSample1});
    CHECK(written(r, ResultFormat::Csv) ==
          "file,texture,texels,labels\r\n"
          "\"amphora \"\"B\"\", fragment 3.ply\",https://collection.example.org/object/42/model/"
          "texture/0,3,\"circular shape, one dominant axis\"\r\n"
          "\"amphora \"\"B\"\", fragment 3.ply\",https://collection.example.org/object/42/model/"
          "texture/1,2,close to circular shape\r\n");

    const QueryResult definition = run_sparql(
        "PREFIX skos: <http://www.w3.org/2004/02/skos/core#>\n"
        "SELECT ?c ?d WHERE { ?c skos:definition ?d }",
        {kSample1, kSample2});
    REQUIRE(definition.rows.size() == 1);
    const std::string text = "Contour sphericity in [0.05, 0.1):\na \"nearly round\" outline.";
    CHECK(definition.rows[0][1] == text);
    CHECK(definition.terms[0][1] ==
          "\"Contour sphericity in [0.05, 0.1):\\na \\\"nearly round\\\" outline.\"@en");
    CHECK(written(definition, ResultFormat::Csv) ==
          "c,d\r\n"
          "https://example.org/dictionaries/sample/close-to-circular-shape,"
          "\"Contour sphericity in [0.05, 0.1):\na \"\"nearly round\"\" outline.\"\r\n");

    SECTION("a result filled by hand: unbound, blank node, carriage return") {
        QueryResult h;
        h.variables = {"a", "b", "c"};
        h.rows = {{"", "_:x1", "one\rtwo"}, {"<http://ex.org/a,b>", "plain", "x"}};
        CHECK(written(h, ResultFormat::Csv) ==
              "a,b,c\r\n"
              ",_:x1,\"one\rtwo\"\r\n"
              "\"http://ex.org/a,b\",plain,x\r\n");
    }
}

TEST_CASE("write_query_result: SPARQL 1.1 results JSON parses back", "[ontology][sparql]") {
    const std::string q = edited(query_file("features-by-significance.rq"), "  # VALUES (?texture)",
                                 "  VALUES (?texture)");
    const QueryResult r = run_sparql(q, {kSample1});
    const auto json = nlohmann::json::parse(written(r, ResultFormat::Json));
    CHECK(
        json.at("head").at("vars") ==
        nlohmann::json::array({"texture", "rank", "feature", "value", "significance", "concept"}));
    const auto& bindings = json.at("results").at("bindings");
    REQUIRE(bindings.size() == 4);
    CHECK(bindings[0].at("texture") ==
          nlohmann::json({{"type", "uri"}, {"value", kB1 + "texture/1"}}));
    CHECK(bindings[0].at("rank") ==
          nlohmann::json({{"type", "literal"}, {"value", "1"}, {"datatype", kXsd + "integer"}}));
    CHECK(bindings[0].at("feature") ==
          nlohmann::json({{"type", "literal"}, {"value", "pca_variance_1"}}));
    CHECK(
        bindings[1].at("value") ==
        nlohmann::json({{"type", "literal"}, {"value", "7.1E-2"}, {"datatype", kXsd + "double"}}));
    CHECK(bindings[1].at("concept") ==
          nlohmann::json(
              {{"type", "literal"}, {"value", "close to circular shape"}, {"xml:lang", "en"}}));
    // Unbound variables are left out of the binding.
    CHECK_FALSE(bindings[0].contains("concept"));
    CHECK_FALSE(bindings[3].contains("rank"));
    CHECK_FALSE(bindings[3].contains("significance"));
    CHECK(bindings[3].at("feature").at("value") == "depth_mean");

    SECTION("escapes, UTF-8, blank nodes and typed literals") {
        const TempFile data(
            "data.ttl",
            "@prefix ex: <http://ex.org/> .\n"
            "_:n ex:text \"tab\\there \\\"quoted\\\" back\\\\slash\\nline\" ;\n"
            "    ex:label \"\xC3\xA9t\xC3\xA9 \xE6\xBC\xA2\"@fr ;\n"
            "    ex:faces \"812-840 902\"^^<https://w3id.org/geotex/ns#faceRanges> .\n");
        const QueryResult e = run_sparql(
            "PREFIX ex: <http://ex.org/>\n"
            "SELECT ?n ?text ?label ?faces WHERE { ?n ex:text ?text ; ex:label ?label ; ex:faces "
            "?faces }",
            {data.path()});
        REQUIRE(e.rows.size() == 1);
        const auto j = nlohmann::json::parse(written(e, ResultFormat::Json));
        const auto& b = j.at("results").at("bindings").at(0);
        CHECK(b.at("n").at("type") == "bnode");
        CHECK(!b.at("n").at("value").get<std::string>().empty());
        CHECK(b.at("text").at("value") == "tab\there \"quoted\" back\\slash\nline");
        CHECK(b.at("label") == nlohmann::json({{"type", "literal"},
                                               {"value", "\xC3\xA9t\xC3\xA9 \xE6\xBC\xA2"},
                                               {"xml:lang", "fr"}}));
        CHECK(b.at("faces").at("datatype") == "https://w3id.org/geotex/ns#faceRanges");
        CHECK(e.terms[0][0].rfind("_:", 0) == 0);
        CHECK(e.rows[0][0] == e.terms[0][0]);
    }
    SECTION("an invalid UTF-8 byte becomes U+FFFD, the document stays valid JSON") {
        QueryResult bad;
        bad.variables = {"v"};
        bad.rows = {
            {"a\xFF"
             "b"}};
        bad.terms = {
            {"\"a\xFF"
             "b\""}};
        const auto j = nlohmann::json::parse(written(bad, ResultFormat::Json));
        CHECK(j.at("results").at("bindings").at(0).at("v").at("value") ==
              "a\xEF\xBF\xBD"
              "b");
    }
    SECTION("no rows") {
        const QueryResult none =
            run_sparql("SELECT ?s WHERE { ?s <http://ex.org/none> ?o }", {kSample1});
        const auto j = nlohmann::json::parse(written(none, ResultFormat::Json));
        CHECK(j.at("head").at("vars") == nlohmann::json::array({"s"}));
        CHECK(j.at("results").at("bindings").empty());
    }
}

TEST_CASE("write_query_result: aligned table, UTF-8 widths, numbers to the right",
          "[ontology][sparql]") {
    QueryResult r;
    r.variables = {"name", "n", "note"};
    r.rows = {{"\xC3\xA9t\xC3\xA9", "3", "two\nlines"}, {"\xE6\xBC\xA2\xE5\xAD\x97", "124", ""}};
    r.terms = {{"\"\xC3\xA9t\xC3\xA9\"@fr", "\"3\"^^<" + kXsd + "integer>", "\"two\\nlines\""},
               {"\"\xE6\xBC\xA2\xE5\xAD\x97\"", "\"124\"^^<" + kXsd + "integer>", ""}};
    // "été" is 3 columns wide, "漢字" 4 (two wide characters).
    CHECK(written(r, ResultFormat::Table) ==
          "name | n   | note\n"
          "-----+-----+-----------\n"
          "\xC3\xA9t\xC3\xA9  |   3 | two\\nlines\n"
          "\xE6\xBC\xA2\xE5\xAD\x97 | 124 |\n"
          "(2 rows)\n");

    const QueryResult q = run_sparql(query_file("objects-with-concept.rq"), {kSample1});
    CHECK(written(q, ResultFormat::Table) ==
          "object                      | mesh                                                  | "
          "textures\n"
          "----------------------------+-------------------------------------------------------+---"
          "------\n"
          "amphora \"B\", fragment 3.ply | <https://collection.example.org/object/42/model/mesh> | "
          "       1\n"
          "(1 row)\n");
}
