// RFC 4180 reading and writing (batch manifests, summaries, query results).

#include <catch2/catch.hpp>

#include "common/detail/csv.hpp"
#include "common/errors.hpp"

using geotex::detail::csv_field;
using geotex::detail::parse_csv;

TEST_CASE("csv: fields, quotes, CRLF, blank lines and line numbers", "[csv]") {
    const auto rows = parse_csv(
        "\xEF\xBB\xBFid,mesh\r\n\r\na,b.ply\n\"x, y\",\"say \"\"hi\"\"\"\n\"two\nlines\",z\n,\n",
        "m.csv");
    REQUIRE(rows.size() == 5);
    CHECK(rows[0].fields == std::vector<std::string>{"id", "mesh"});  // BOM and CR removed
    CHECK(rows[0].line == 1);
    CHECK(rows[1].fields == std::vector<std::string>{"a", "b.ply"});
    CHECK(rows[1].line == 3);  // the empty line 2 is skipped but counted
    CHECK(rows[2].fields == std::vector<std::string>{"x, y", "say \"hi\""});
    CHECK(rows[3].fields == std::vector<std::string>{"two\nlines", "z"});
    CHECK(rows[3].line == 5);
    CHECK(rows[4].fields ==
          std::vector<std::string>{"", ""});  // a lone comma is a row of two empty fields
    CHECK(rows[4].line == 7);
    CHECK(parse_csv("", "e.csv").empty());
    CHECK(parse_csv("a", "e.csv").at(0).fields ==
          std::vector<std::string>{"a"});  // no final newline
}

TEST_CASE("csv: an unclosed quote and text after a quote are errors with their line", "[csv]") {
    try {
        parse_csv("id,mesh\na,\"b.ply\nc,d\n", "m.csv");
        FAIL("no error");
    } catch (const geotex::ParseError& e) {
        CHECK(e.located() == "m.csv:2: quoted field opened here is never closed");
    }
    try {
        parse_csv("id,mesh\n\"a\"b,c\n", "m.csv");
        FAIL("no error");
    } catch (const geotex::ParseError& e) {
        CHECK(e.line() == 2);
    }
}

TEST_CASE("csv: a written field reads back as itself", "[csv]") {
    for (const std::string field :
         {"plain", "with, comma", "say \"hi\"", "two\nlines", "cr\r\nlf", "", "été"}) {
        const auto rows = parse_csv(csv_field(field) + ",end\n", "t.csv");
        REQUIRE(rows.size() == 1);
        CHECK(rows[0].fields == std::vector<std::string>{field, "end"});
    }
    CHECK(csv_field("plain") == "plain");
    CHECK(csv_field("a,b") == "\"a,b\"");
}
