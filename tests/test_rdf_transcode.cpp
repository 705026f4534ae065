// Tests of ontology/rdf_transcode.cpp (Turtle to N-Triples chunks and to N-Quads) and of
// validate_iri, on the fixture tests/data/annotation-sample.ttl and hand-written Turtle.

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "ontology/rdf_transcode.hpp"
#include "ontology/rdf_writer.hpp"
#include "ontology/sparql.hpp"

#ifndef GEOTEX_SOURCE_DIR
#error "GEOTEX_SOURCE_DIR (the repository root) must be defined"
#endif

using geotex::InvalidInput;
using geotex::make_ntriples_chunks;
using geotex::NQuadsWriter;
using geotex::NTriplesChunkParams;
using geotex::ParseError;

namespace {

const std::string kSample = std::string(GEOTEX_SOURCE_DIR) + "/tests/data/annotation-sample.ttl";

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    return lines;
}

/// The triples of N-Triples or N-Quads `text` as read back by an independent path: the
/// embedded SPARQL engine (Raptor's parser into Rasqal), via a temporary file.
std::multiset<std::string> read_back(const std::string& text, const std::string& extension) {
    const std::string path = "rdf_transcode_test_read_back" + extension;
    {
        std::ofstream out(path, std::ios::binary);
        out << text;
    }
    const geotex::QueryResult r =
        geotex::run_sparql("SELECT ?s ?p ?o WHERE { ?s ?p ?o }", std::vector<std::string>{path});
    std::remove(path.c_str());
    std::multiset<std::string> triples;
    for (const auto& row : r.terms) triples.insert(row[0] + " " + row[1] + " " + row[2]);
    return triples;
}

}  // namespace

TEST_CASE("make_ntriples_chunks: chunks of at most max_triples whose union is the document",
          "[ontology][transcode]") {
    const std::string text = read_text(kSample);
    const auto whole = make_ntriples_chunks(text, kSample);
    REQUIRE(whole.chunks.size() == 1);
    CHECK(whole.num_triples == 266);  // rapper -c counts 266 triples in the fixture
    CHECK_FALSE(whole.has_blank_nodes);
    const std::multiset<std::string> expected = read_back(whole.chunks[0], ".nt");
    CHECK(expected.size() == 266);

    for (std::size_t max : {1u, 7u, 100u, 265u, 266u, 267u}) {
        NTriplesChunkParams params;
        params.max_triples = max;
        const auto cut = make_ntriples_chunks(text, kSample, params);
        CHECK(cut.num_triples == 266);
        CHECK(cut.chunks.size() == (266 + max - 1) / max);
        std::string joined;
        for (const std::string& c : cut.chunks) {
            CHECK(lines_of(c).size() <= max);
            CHECK(read_back(c, ".nt").size() == lines_of(c).size());  // each chunk parses alone
            joined += c;
        }
        CHECK(joined == whole.chunks[0]);  // same lines, same order
    }
}

TEST_CASE("make_ntriples_chunks: empty document, blank nodes, and its preconditions",
          "[ontology][transcode]") {
    const auto empty = make_ntriples_chunks("@prefix x: <urn:x:> .\n", "empty.ttl");
    CHECK(empty.num_triples == 0);
    CHECK(empty.chunks.empty());

    const auto blank = make_ntriples_chunks("<urn:a> <urn:b> [ <urn:c> 1 ] .\n", "b.ttl");
    CHECK(blank.num_triples == 2);
    CHECK(blank.has_blank_nodes);

    NTriplesChunkParams zero;
    zero.max_triples = 0;
    CHECK_THROWS_AS(make_ntriples_chunks("<urn:a> <urn:b> <urn:c> .", "z.ttl", zero), InvalidInput);
    try {
        make_ntriples_chunks("<urn:a> <urn:b> <urn:c> .\n<urn:a> <urn:b> \"open .\n", "bad.ttl");
        FAIL("invalid Turtle accepted");
    } catch (const ParseError& e) {
        CHECK(e.file() == "bad.ttl");
        CHECK(e.line() == 2);
    }
}

TEST_CASE("NQuadsWriter: each document in its graph, deterministic, blank nodes kept apart",
          "[ontology][transcode]") {
    const std::string doc = "<urn:a> <urn:p> _:n .\n_:n <urn:q> \"é \\\"x\\\"\\n\"@fr .\n";
    const auto write = [&] {
        std::ostringstream out;
        NQuadsWriter w(out);
        CHECK(w.add(doc, "one.ttl", "https://example.org/g/1") == 2);
        CHECK(w.add(doc, "two.ttl", "urn:g:2") == 2);
        w.finish();
        return out.str();
    };
    const std::string nq = write();
    CHECK(write() == nq);
    const std::vector<std::string> quads = lines_of(nq);
    REQUIRE(quads.size() == 4);
    CHECK(quads[0].find("<https://example.org/g/1> .") != std::string::npos);
    CHECK(quads[3].find("<urn:g:2> .") != std::string::npos);
    // The blank node of each document is one node there, and not the other document's.
    std::set<std::string> labels;
    for (const auto& q : quads) {
        const auto at = q.find("_:");
        REQUIRE(at != std::string::npos);
        labels.insert(q.substr(at, q.find(' ', at) - at));
    }
    CHECK(labels.size() == 2);
    // The triples read back (graphs aside) are the document's, twice.
    CHECK(read_back(nq, ".nq").size() == 4);
}

TEST_CASE("NQuadsWriter: a document that does not parse leaves nothing; bad graph IRIs refused",
          "[ontology][transcode]") {
    std::ostringstream out;
    NQuadsWriter w(out);
    CHECK(w.add("<urn:a> <urn:b> <urn:c> .\n", "a.ttl", "urn:g:a") == 1);
    CHECK_THROWS_AS(w.add("<urn:a> <urn:b> <urn:c> .\n<urn:a> <urn:b> .\n", "b.ttl", "urn:g:b"),
                    ParseError);
    CHECK_THROWS_AS(w.add("<urn:a> <urn:b> <urn:c> .\n", "c.ttl", "a graph"), InvalidInput);
    CHECK_THROWS_AS(w.add("<urn:a> <urn:b> <urn:c> .\n", "c.ttl", "no-scheme"), InvalidInput);
    CHECK(w.add("<urn:d> <urn:b> <urn:c> .\n", "d.ttl", "urn:g:d") == 1);
    w.finish();
    const auto quads = lines_of(out.str());
    REQUIRE(quads.size() == 2);
    CHECK(quads[0] == "<urn:a> <urn:b> <urn:c> <urn:g:a> .");
    CHECK(quads[1] == "<urn:d> <urn:b> <urn:c> <urn:g:d> .");
}

TEST_CASE("validate_iri: the rules of validate_base_iri without the trailing / or #",
          "[ontology][transcode]") {
    CHECK(geotex::validate_iri("https://example.org/object/vase-12") ==
          "https://example.org/object/vase-12");
    CHECK(geotex::validate_iri("urn:geotex:collection") == "urn:geotex:collection");
    for (const char* bad : {"", "relative/path", "https://example.org/a b", "https://x/<y>",
                            "https://x/a/../b", "https://x/%zz"})
        CHECK_THROWS_AS(geotex::validate_iri(bad, "graph IRI"), InvalidInput);
    CHECK_THROWS_WITH(geotex::validate_iri("https://x/a b", "graph IRI"),
                      Catch::Contains("graph IRI 'https://x/a b'"));
    CHECK_THROWS_AS(geotex::validate_base_iri("https://example.org/no-end"), InvalidInput);
}
