// What geotex query refuses or limits (ontology/sparql.cpp, detail/sparql_checks.cpp):
// syntax errors and broken data files named, only SELECT and ASK, SERVICE and updates refused
// at their place, the time limit, a byte order mark, U+0000 kept.

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "tests/sparql_test_support.hpp"

using namespace geotex::sparql_test;

// ---- errors ---------------------------------------------------------------------------

TEST_CASE("run_sparql: a query syntax error is a ParseError with its line", "[ontology][sparql]") {
    const std::string q = "SELECT ?s\nWHERE {\n  ?s ?p ?o .\n  FILTER NOT EXISTS { ?s ?p 3 }\n}\n";
    try {
        run_sparql(q, {kSample1});
        FAIL("no exception");
    } catch (const geotex::ParseError& e) {
        CHECK(e.line() == 4);
        CHECK(std::string(e.what()).find("syntax error") != std::string::npos);
        CHECK(e.file().empty());  // the caller knows the query file
    }
    CHECK_THROWS_AS(run_sparql("SELECT ?s WHERE { ?s ?p ?o", {kSample1}), geotex::ParseError);
}

TEST_CASE("run_sparql: a missing or broken data file is named", "[ontology][sparql]") {
    const std::string q = "SELECT ?s WHERE { ?s ?p ?o }";
    const std::string missing = kRoot + "/tests/data/no-such-file.ttl";
    try {
        run_sparql(q, {kSample1, missing});
        FAIL("no exception");
    } catch (const geotex::IoError& e) {
        CHECK(e.file() == missing);
        CHECK(e.located().find("no-such-file.ttl") != std::string::npos);
    }

    const TempFile broken(
        "broken.ttl", "@prefix ex: <http://ex.org/> .\nex:a ex:p \"x\" .\nex:b ex:p ex:c ex:d .\n");
    try {
        run_sparql(q, {kSample1, broken.path()});
        FAIL("no exception");
    } catch (const geotex::ParseError& e) {
        CHECK(e.file() == broken.path());
        CHECK(e.line() == 3);
    }

    const TempFile unknown("data.json", "{}");
    try {
        run_sparql(q, {unknown.path()});
        FAIL("no exception");
    } catch (const geotex::InvalidInput& e) {
        CHECK(e.file() == unknown.path());
    }
    CHECK_THROWS_AS(run_sparql(q, {kRoot + "/tests/data"}), geotex::IoError);
}

TEST_CASE("run_sparql: only SELECT and ASK", "[ontology][sparql]") {
    CHECK_THROWS_AS(run_sparql("CONSTRUCT { ?s ?p ?o } WHERE { ?s ?p ?o }", {kSample1}),
                    geotex::InvalidInput);
    CHECK_THROWS_WITH(run_sparql("CONSTRUCT { ?s ?p ?o } WHERE { ?s ?p ?o }", {kSample1}),
                      Catch::Contains("only SELECT and ASK"));
    CHECK_THROWS_AS(run_sparql("DESCRIBE <http://ex.org/a>", {kSample1}), geotex::InvalidInput);
    CHECK_THROWS_AS(
        run_sparql("SELECT ?s FROM <http://example.org/remote.ttl> WHERE { ?s ?p ?o }", {kSample1}),
        geotex::InvalidInput);
}

TEST_CASE("run_sparql: refuses what Rasqal 0.9.33 runs wrongly", "[ontology][sparql]") {
    // One-variable VALUES: wrong rows inside the pattern, a crash after the WHERE clause.
    try {
        run_sparql(
            "SELECT ?s WHERE {\n  # VALUES ?x in a comment is fine\n  VALUES ?s { <http://a> }\n}",
            {kSample1});
        FAIL("no exception");
    } catch (const geotex::InvalidInput& e) {
        CHECK(e.line() == 3);
        CHECK(e.column() == 3);
        CHECK(std::string(e.what()).find("VALUES (?x)") != std::string::npos);
    }
    CHECK_THROWS_AS(run_sparql("SELECT ?s WHERE { ?s ?p ?o } values $s { <http://a> }", {kSample1}),
                    geotex::InvalidInput);
    // Not a VALUES clause: a string, an IRI, a prefixed name, a variable.
    CHECK_NOTHROW(
        run_sparql("PREFIX values: <http://ex.org/VALUES?x>\n"
                   "SELECT ?values WHERE { ?values ?p \"VALUES ?x\" . ?values values:p ?o }",
                   {kSample1}));
    // MINUS fails when run: an error that says what to do.
    CHECK_THROWS_WITH(run_sparql("SELECT ?s WHERE { ?s ?p ?o MINUS { ?s a ?t } }", {kSample1}),
                      Catch::Contains("OPTIONAL"));
}

// ---------------------------------------------------------------------------------------
// Hostile queries and data (issue 17, findings 3, 7 and 11)

TEST_CASE("run_sparql: SERVICE is refused at its keyword, before anything is fetched",
          "[ontology][sparql]") {
    // A file and a port where nothing listens: either would be read (or refused by the
    // network) only once Rasqal runs; the error comes first, with the keyword's place.
    const std::vector<std::pair<std::string, std::pair<long, long>>> queries = {
        {"SELECT * WHERE {\n  ?s ?p ?o .\n  SERVICE <file:///etc/passwd> { ?a ?b ?c }\n}", {3, 3}},
        {"SELECT * WHERE { ?s ?p ?o OPTIONAL { service SILENT <http://127.0.0.1:1/> { ?a ?b ?c } } "
         "}",
         {1, 38}},
        {"PREFIX x: <http://ex.org/>\nSELECT * WHERE { SERVICE ?endpoint { ?a ?b ?c } }", {2, 18}},
    };
    for (const auto& [query, place] : queries) {
        try {
            run_sparql(query, {kSample1});
            FAIL("no exception: " << query);
        } catch (const geotex::InvalidInput& e) {
            CHECK(e.line() == place.first);
            CHECK(e.column() == place.second);
            CHECK_THAT(e.what(), Catch::Contains("SERVICE is refused"));
        }
    }
    // The word in a string, an IRI, a comment or a prefixed name is no SERVICE.
    CHECK_NOTHROW(
        run_sparql("PREFIX SERVICE: <http://ex.org/SERVICE>\n"
                   "# SERVICE <http://ex.org/>\n"
                   "SELECT ?s WHERE { ?s ?p ?o FILTER(?o != \"SERVICE <http://x/>\" && "
                   "?p != SERVICE:p) }",
                   {kSample1}));
    // LOAD and updates are no SPARQL query: refused at their keyword, before Rasqal parses.
    for (const auto& [update, column] : std::vector<std::pair<std::string, long>>{
             {"LOAD <file:///etc/passwd>", 1},
             {"PREFIX a: <http://a/>\n  insert DATA { a:a a:b a:c }", 3},
             {"WITH <http://g> DELETE { ?s ?p ?o } WHERE { ?s ?p ?o }", 1}}) {
        try {
            run_sparql(update, {kSample1});
            FAIL("no exception: " << update);
        } catch (const geotex::InvalidInput& e) {
            CHECK(e.column() == column);
            CHECK_THAT(e.what(), Catch::Contains("is refused") && Catch::Contains("SPARQL Update"));
        }
    }
    // The words as prefixed names, variables or in strings are no update.
    CHECK_NOTHROW(
        run_sparql("PREFIX load: <http://ex.org/>\nSELECT ?delete WHERE { ?delete ?p "
                   "\"INSERT DATA\" }",
                   {kSample1}));
}

TEST_CASE("run_sparql: a query that runs past its timeout ends with QueryTimeout",
          "[ontology][sparql]") {
    // The query: a four-way cross join over 200 triples, 1.6e9 rows, which runs for
    // hours; stopped at 0.3 s, it throws instead of returning the rows counted so far.
    std::string data;
    for (int i = 0; i < 200; ++i)
        data += "<http://ex.org/s" + std::to_string(i) + "> <http://ex.org/p" +
                std::to_string(i % 7) + "> \"v" + std::to_string(i) + "\" .\n";
    const TempFile file("d200.nt", data);
    geotex::QueryParams params;
    params.timeout = 0.3;
    const std::string cross =
        "SELECT (COUNT(*) AS ?n) WHERE { ?a ?p ?o . ?b ?p2 ?o2 . ?c ?p3 ?o3 . ?d ?p4 ?o4 }";
    CHECK_THROWS_AS(run_sparql(cross, {file.path()}, params), geotex::QueryTimeout);
    CHECK_THROWS_WITH(run_sparql(cross, {file.path()}, params), Catch::Contains("ran out of time"));
    // Rows rather than an aggregate: the same.
    CHECK_THROWS_AS(
        run_sparql("SELECT * WHERE { ?a ?p ?o . ?b ?p2 ?o2 . ?c ?p3 ?o3 }", {file.path()}, params),
        geotex::QueryTimeout);
    // A query that ends in time gives its whole answer: 200 * 200 pairs.
    params.timeout = 600;
    const QueryResult pairs = run_sparql("SELECT (COUNT(*) AS ?n) WHERE { ?a ?p ?o . ?b ?p2 ?o2 }",
                                         {file.path()}, params);
    REQUIRE(pairs.rows.size() == 1);
    CHECK(pairs.rows[0][0] == "40000");
    for (double bad : {-1.0, std::nan(""), HUGE_VAL}) {
        params.timeout = bad;
        CHECK_THROWS_AS(run_sparql("ASK {}", {file.path()}, params), geotex::InvalidInput);
    }
}

TEST_CASE("run_sparql: a byte order mark before the query is skipped", "[ontology][sparql]") {
    const std::string query = "SELECT (COUNT(*) AS ?n) WHERE { ?s ?p ?o }";
    const QueryResult plain = run_sparql(query, {kSample1});
    const QueryResult with_bom = run_sparql("\xEF\xBB\xBF" + query, {kSample1});
    CHECK(with_bom.rows == plain.rows);
    // Columns of line 1 are counted after it.
    try {
        run_sparql("\xEF\xBB\xBFSELECT * WHERE { SERVICE <http://a/> {} }", {kSample1});
        FAIL("no exception");
    } catch (const geotex::InvalidInput& e) {
        CHECK(e.column() == 18);
    }
}

TEST_CASE("run_sparql: a literal holding U+0000 is kept whole in every result format",
          "[ontology][sparql]") {
    // Raptor's parsers cut a value at a decoded \u0000; an escaped backslash before u0000 is
    // six characters of text.
    const TempFile file("nul.nt",
                        "<http://ex.org/a> <http://ex.org/p> \"a\\u0000b\" .\n"
                        "<http://ex.org/b> <http://ex.org/p> \"c\\\\u0000d\\U00000000\"@en .\n");
    const QueryResult r = run_sparql("SELECT ?o WHERE { ?s ?p ?o } ORDER BY ?s", {file.path()});
    REQUIRE(r.rows.size() == 2);
    CHECK(r.rows[0][0] == std::string("a\0b", 3));
    CHECK(r.rows[1][0] == std::string("c\\u0000d\0", 9));
    const auto json = nlohmann::json::parse(written(r, ResultFormat::Json));
    CHECK(json["results"]["bindings"][0]["o"]["value"] == std::string("a\0b", 3));
    CHECK(json["results"]["bindings"][1]["o"]["xml:lang"] == "en");
    CHECK(written(r, ResultFormat::Csv) == "o\r\na\\u0000b\r\nc\\u0000d\\u0000\r\n");
    CHECK_THAT(written(r, ResultFormat::Table), Catch::Contains("a\\u0000b"));
    // A file that also holds U+FDD0 (geotex's stand-in while Raptor reads) is refused.
    const TempFile both("both.nt",
                        "<http://ex.org/a> <http://ex.org/p> \"a\\u0000b\" .\n"
                        "<http://ex.org/a> <http://ex.org/p> \"\xEF\xB7\x90\" .\n");
    CHECK_THROWS_AS(run_sparql("ASK {}", {both.path()}), geotex::InvalidInput);
}
