// Tests of the embedded SPARQL (ontology/sparql.cpp) and of the documented queries of
// ontology/queries/ on the hand-written fixtures tests/data/annotation-sample*.ttl.

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/errors.hpp"
#include "ontology/sparql.hpp"

#ifndef GEOTEX_SOURCE_DIR
#error "GEOTEX_SOURCE_DIR (the repository root) must be defined"
#endif

using geotex::QueryResult;
using geotex::ResultFormat;
using geotex::run_sparql;
using Rows = std::vector<std::vector<std::string>>;

namespace {

const std::string kRoot = GEOTEX_SOURCE_DIR;
const std::string kSample1 = kRoot + "/tests/data/annotation-sample.ttl";
const std::string kSample2 = kRoot + "/tests/data/annotation-sample2.ttl";
const std::string kB1 = "https://collection.example.org/object/42/model/";
const std::string kB2 =
    "urn:sha256:31a8e0614cf6ac52dbe268ebcebf6c5c33e1742d5c6038b8e90b282f1851de92/";
const std::string kAmphora = "amphora \"B\", fragment 3.ply";
const std::string kXsd = "http://www.w3.org/2001/XMLSchema#";

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string query_file(const std::string& name) {
    return read_text(kRoot + "/ontology/queries/" + name);
}

/// `text` with its one occurrence of `from` replaced by `to` (the way a user edits a
/// query's parameter).
std::string edited(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    REQUIRE(text.find(from, at + 1) == std::string::npos);
    return text.replace(at, from.size(), to);
}

std::string written(const QueryResult& r, ResultFormat format) {
    std::ostringstream out;
    geotex::write_query_result(out, r, format);
    return out.str();
}

/// A file in a fresh temporary directory, removed with the object.
class TempFile {
  public:
    TempFile(const std::string& name, const std::string& content) {
        // The process id keeps apart the test processes that ctest runs in parallel.
        dir_ = std::filesystem::temp_directory_path() /
               ("geotex-test-sparql-" + std::to_string(::getpid()) + "-" +
                std::to_string(counter()++));
        std::filesystem::create_directories(dir_);
        path_ = (dir_ / name).string();
        std::ofstream(path_, std::ios::binary) << content;
    }
    ~TempFile() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    const std::string& path() const { return path_; }

  private:
    static int& counter() {
        static int n = 0;
        return n;
    }
    std::filesystem::path dir_;
    std::string path_;
};

/// The first fixture without its dictionary section: what `geotex annotate` writes alone.
std::string sample1_without_dictionary() {
    const std::string text = read_text(kSample1);
    const auto at = text.find("# ---- the dictionary");
    REQUIRE(at != std::string::npos);
    return text.substr(0, at);
}

const std::vector<std::string> kQueryFiles = {"textures-with-concept.rq", "texels-per-texture.rq",
                                              "features-by-significance.rq",
                                              "objects-with-concept.rq", "texture-labels.rq"};

}  // namespace

// ---- the documented queries ------------------------------------------------------------

TEST_CASE("run_sparql: textures-with-concept.rq, the textures whose annotation has the concept",
          "[ontology][sparql]") {
    const std::string q = query_file("textures-with-concept.rq");
    const QueryResult r = run_sparql(q, {kSample1, kSample2});
    CHECK(r.variables == std::vector<std::string>{"file", "texture", "texels"});
    CHECK(r.rows == Rows{{kAmphora, "<" + kB1 + "texture/0>", "3"},
                         {"sphere-1.ply", "<" + kB2 + "texture/0>", "4"},
                         {"sphere-1.ply", "<" + kB2 + "texture/1>", "2"}});
    CHECK_FALSE(r.is_boolean);

    SECTION("several concept ids") {
        const QueryResult two = run_sparql(
            edited(q, "VALUES (?id) { (\"circular-shape\") }",
                   "VALUES (?id) { (\"circular-shape\") (\"close-to-circular-shape\") }"),
            {kSample1, kSample2});
        CHECK(two.rows == Rows{{kAmphora, "<" + kB1 + "texture/0>", "3"},
                               {kAmphora, "<" + kB1 + "texture/1>", "2"},
                               {"sphere-1.ply", "<" + kB2 + "texture/0>", "4"},
                               {"sphere-1.ply", "<" + kB2 + "texture/1>", "2"}});
    }
    SECTION("the concept chosen by a label or by IRI") {
        const std::string by_id =
            "  VALUES (?id) { (\"circular-shape\") }\n  ?concept skos:notation ?id .\n";
        const std::string by_label =
            edited(q, by_id, "  ?concept skos:prefLabel \"forme proche du cercle\"@fr .\n");
        CHECK(run_sparql(by_label, {kSample1, kSample2}).rows ==
              Rows{{kAmphora, "<" + kB1 + "texture/1>", "2"}});
        const std::string by_iri = edited(
            q, by_id,
            "  VALUES (?concept) { (<https://example.org/dictionaries/sample/one-dominant-axis>) "
            "}\n");
        CHECK(run_sparql(by_iri, {kSample1, kSample2}).rows ==
              Rows{{kAmphora, "<" + kB1 + "texture/0>", "3"},
                   {"sphere-1.ply", "<" + kB2 + "texture/1>", "2"}});
        // Without the dictionary's triples, an IRI still finds the textures; an id does not
        // (`geotex annotate` always writes the dictionary).
        const TempFile alone("annotation.ttl", sample1_without_dictionary());
        CHECK(run_sparql(by_iri, {alone.path()}).rows ==
              Rows{{kAmphora, "<" + kB1 + "texture/0>", "3"}});
        CHECK(run_sparql(q, {alone.path()}).rows.empty());
    }
}

TEST_CASE("run_sparql: texels-per-texture.rq, texel count and total faces of every texture",
          "[ontology][sparql]") {
    const std::string q = query_file("texels-per-texture.rq");
    const Rows expected = {{kAmphora, "<" + kB1 + "texture/0>", "3", "124"},
                           {kAmphora, "<" + kB1 + "texture/1>", "2", "113"},
                           {"sphere-1.ply", "<" + kB2 + "texture/0>", "4", "200"},
                           {"sphere-1.ply", "<" + kB2 + "texture/1>", "2", "160"},
                           {"sphere-1.ply", "<" + kB2 + "texture/2>", "1", "30"}};
    const QueryResult r = run_sparql(q, {kSample1, kSample2});
    CHECK(r.variables == std::vector<std::string>{"file", "texture", "texels", "faces"});
    CHECK(r.rows == expected);
    // The files in the other order: the same rows in the same order (ORDER BY).
    CHECK(run_sparql(q, {kSample2, kSample1}).rows == expected);
    CHECK(r.terms[0][1] == "<" + kB1 + "texture/0>");
    CHECK(r.terms[0][2] == "\"3\"^^<" + kXsd + "integer>");
    CHECK(r.terms[0][3] == "\"124\"^^<" + kXsd + "integer>");
    // No texel at all: no row (geotex drops the group with unbound keys that Rasqal 0.9.33
    // gives for a GROUP BY over no solution).
    const TempFile other("other.ttl", "<http://ex.org/a> <http://ex.org/p> \"x\" .\n");
    CHECK(run_sparql(q, {other.path()}).rows.empty());
    CHECK(run_sparql(query_file("texture-labels.rq"), {other.path()}).rows.empty());
}

TEST_CASE("run_sparql: features-by-significance.rq, measurements ranked, unranked last",
          "[ontology][sparql]") {
    const std::string q = query_file("features-by-significance.rq");
    const std::string t0 = "<" + kB1 + "texture/0>";
    const std::string t1 = "<" + kB1 + "texture/1>";
    const QueryResult r = run_sparql(q, {kSample1});
    CHECK(r.variables == std::vector<std::string>{"texture", "rank", "feature", "value",
                                                  "significance", "concept"});
    CHECK(r.rows ==
          Rows{{t0, "1", "contour_sphericity", "2.1E-2", "3.1E-1", "circular shape"},
               {t0, "2", "pca_variance_1", "7.2E-1", "4.5E-1", "one dominant axis"},
               {t0, "3", "area", "3.3E-1", "6.2E-1", ""},
               {t0, "", "depth_mean", "5E-1", "", ""},
               {t1, "1", "pca_variance_1", "4.1E-1", "2.2E-1", ""},
               {t1, "2", "contour_sphericity", "7.1E-2", "5E-1", "close to circular shape"},
               {t1, "3", "area", "8.8E-1", "9.5E-1", ""},
               {t1, "", "depth_mean", "5E-1", "", ""}});
    // Unbound cells are empty terms; the value keeps its lexical form and datatype.
    CHECK(r.terms[3][1].empty());
    CHECK(r.terms[3][3] == "\"5E-1\"^^<" + kXsd + "double>");
    CHECK(r.terms[1][5] == "\"one dominant axis\"@en");

    SECTION("one texture, labels in French") {
        const std::string one = edited(edited(q, "  # VALUES (?texture)", "  VALUES (?texture)"),
                                       "= \"en\"", "= \"fr\"");
        CHECK(run_sparql(one, {kSample1, kSample2}).rows ==
              Rows{{t1, "1", "pca_variance_1", "4.1E-1", "2.2E-1", ""},
                   {t1, "2", "contour_sphericity", "7.1E-2", "5E-1", "forme proche du cercle"},
                   {t1, "3", "area", "8.8E-1", "9.5E-1", ""},
                   {t1, "", "depth_mean", "5E-1", "", ""}});
    }
    SECTION("without the dictionary, the concept's IRI") {
        const TempFile alone("annotation.ttl", sample1_without_dictionary());
        const QueryResult ids = run_sparql(q, {alone.path()});
        REQUIRE(ids.rows.size() == 8);
        const std::string sample = "https://example.org/dictionaries/sample/";
        CHECK(ids.rows[0][5] == sample + "circular-shape");
        CHECK(ids.rows[1][5] == sample + "one-dominant-axis");
        CHECK(ids.rows[5][5] == sample + "close-to-circular-shape");
    }
}

TEST_CASE("run_sparql: objects-with-concept.rq, objects of several files carrying a concept",
          "[ontology][sparql]") {
    const std::string q = query_file("objects-with-concept.rq");
    const Rows expected = {{kAmphora, "<" + kB1 + "mesh>", "1"},
                           {"sphere-1.ply", "<" + kB2 + "mesh>", "2"}};
    const QueryResult r = run_sparql(q, {kSample1, kSample2});
    CHECK(r.variables == std::vector<std::string>{"object", "mesh", "textures"});
    CHECK(r.rows == expected);
    CHECK(run_sparql(q, {kSample2, kSample1}).rows == expected);
    CHECK(run_sparql(q, {kSample2}).rows == Rows{expected[1]});

    const std::string dominant = edited(q, "VALUES (?id) { (\"circular-shape\") }",
                                        "VALUES (?id) { (\"one-dominant-axis\") }");
    CHECK(run_sparql(dominant, {kSample1, kSample2}).rows ==
          Rows{{kAmphora, "<" + kB1 + "mesh>", "1"}, {"sphere-1.ply", "<" + kB2 + "mesh>", "1"}});
    const std::string none = edited(q, "VALUES (?id) { (\"circular-shape\") }",
                                    "VALUES (?id) { (\"no-such-concept\") }");
    CHECK(run_sparql(none, {kSample1, kSample2}).rows.empty());
}

TEST_CASE("run_sparql: texture-labels.rq, every texture with its concept labels in one language",
          "[ontology][sparql]") {
    const std::string q = query_file("texture-labels.rq");
    const QueryResult r = run_sparql(q, {kSample1, kSample2});
    CHECK(r.variables == std::vector<std::string>{"file", "texture", "texels", "labels"});
    CHECK(r.rows ==
          Rows{{kAmphora, "<" + kB1 + "texture/0>", "3", "circular shape, one dominant axis"},
               {kAmphora, "<" + kB1 + "texture/1>", "2", "close to circular shape"},
               {"sphere-1.ply", "<" + kB2 + "texture/0>", "4", "circular shape"},
               {"sphere-1.ply", "<" + kB2 + "texture/1>", "2", "circular shape, one dominant axis"},
               {"sphere-1.ply", "<" + kB2 + "texture/2>", "1", ""}});

    const QueryResult fr = run_sparql(edited(q, "= \"en\"", "= \"fr\""), {kSample1, kSample2});
    REQUIRE(fr.rows.size() == 5);
    CHECK(fr.rows[0][3] == "forme circulaire, un axe dominant");
    CHECK(fr.rows[1][3] == "forme proche du cercle");
    CHECK(fr.rows[3][3] == "forme circulaire, un axe dominant");

    // Without the dictionary, the concepts' IRIs.
    const TempFile alone("annotation.ttl", sample1_without_dictionary());
    const std::string sample = "https://example.org/dictionaries/sample/";
    CHECK(run_sparql(q, {alone.path()}).rows ==
          Rows{{kAmphora, "<" + kB1 + "texture/0>", "3",
                sample + "circular-shape, " + sample + "one-dominant-axis"},
               {kAmphora, "<" + kB1 + "texture/1>", "2", sample + "close-to-circular-shape"}});
    // A texture without concepts: the empty string, in every engine.
    CHECK(r.terms[4][3] == "\"\"");
}

TEST_CASE("run_sparql: every documented query has its header and runs", "[ontology][sparql]") {
    for (const std::string& name : kQueryFiles) {
        INFO(name);
        const std::string q = query_file(name);
        CHECK(q.rfind("# " + name + ":", 0) == 0);
        CHECK(q.find("# Run: geotex query ontology/queries/" + name) != std::string::npos);
        CHECK(q.find("Example row") != std::string::npos);
        CHECK_FALSE(run_sparql(q, {kSample1, kSample2}).rows.empty());
    }
}

// The cross-object queries; their rows on a collection are checked by
// tests/collection_queries_test.sh. The fixtures have no dictionary version node, so
// old-dictionary-version.rq has no row on them (see its own test below).
const std::vector<std::string> kCollectionQueryFiles = {
    "objects-sharing-concept.rq", "feature-distribution.rq", "old-dictionary-version.rq"};

TEST_CASE("run_sparql: the cross-object queries have their header and run", "[ontology][sparql]") {
    for (const std::string& name : kCollectionQueryFiles) {
        INFO(name);
        const std::string q = query_file(name);
        CHECK(q.rfind("# " + name + ":", 0) == 0);
        CHECK(q.find("# Run: geotex query ontology/queries/" + name) != std::string::npos);
        CHECK(q.find("Example row") != std::string::npos);
        CHECK_NOTHROW(run_sparql(q, {kSample1, kSample2}));
    }
    // The two fixtures share "circular-shape" (twice in sphere-1) and "one-dominant-axis".
    const QueryResult shared =
        run_sparql(query_file("objects-sharing-concept.rq"), {kSample1, kSample2});
    REQUIRE(shared.rows.size() == 2);
    CHECK(shared.rows[0][2] == "<https://example.org/dictionaries/sample/circular-shape>");
    CHECK(shared.rows[0][3] == "circular shape");
    CHECK(shared.rows[1][2] == "<https://example.org/dictionaries/sample/one-dominant-axis>");
}

TEST_CASE("run_sparql: old-dictionary-version.rq, with the version nodes of before and after "
          "issue 16",
          "[ontology][sparql]") {
    // a.ply and b.ply: runs that use the shared version node N scheme/version/<v> (issue 16);
    // c.ply: a run with its own B run/dictionary node (before). No IRI prefix is shared.
    const TempFile data(
        "versions.ttl",
        "@prefix gtx: <https://w3id.org/geotex/ns#> .\n"
        "@prefix prov: <http://www.w3.org/ns/prov#> .\n"
        "@prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
        "@prefix dcterms: <http://purl.org/dc/terms/> .\n"
        "@prefix d: <https://w3id.org/geotex/dictionary/default/> .\n"
        "<ni:///sha-256;AAAA> a gtx:Mesh ; dcterms:identifier \"a.ply\" .\n"
        "<ni:///sha-256;BBBB> a gtx:Mesh ; dcterms:identifier \"b.ply\" .\n"
        "<ni:///sha-256;KKKA#run> a gtx:TextureAnalysis ;\n"
        "    prov:used <ni:///sha-256;AAAA>, <https://w3id.org/geotex/dictionary/default/scheme/version/0.9> .\n"
        "<ni:///sha-256;KKKB#run> a gtx:TextureAnalysis ;\n"
        "    prov:used <ni:///sha-256;BBBB>, <https://w3id.org/geotex/dictionary/default/scheme/version/1.0> .\n"
        "<https://w3id.org/geotex/dictionary/default/scheme/version/0.9> a gtx:DictionaryVersion, prov:Entity ;\n"
        "    dcterms:isVersionOf d:scheme ; prov:specializationOf d:scheme ; owl:versionInfo \"0.9\" .\n"
        "<https://w3id.org/geotex/dictionary/default/scheme/version/1.0> a gtx:DictionaryVersion, prov:Entity ;\n"
        "    dcterms:isVersionOf d:scheme ; prov:specializationOf d:scheme ; owl:versionInfo \"1.0\" .\n"
        "d:scheme dcterms:hasVersion <https://w3id.org/geotex/dictionary/default/scheme/version/0.9>,\n"
        "    <https://w3id.org/geotex/dictionary/default/scheme/version/1.0> .\n"
        "<https://example.org/c/mesh> a gtx:Mesh ; dcterms:identifier \"c.ply\" .\n"
        "<https://example.org/c/run> a gtx:TextureAnalysis ;\n"
        "    prov:used <https://example.org/c/mesh>, d:scheme, <https://example.org/c/run/dictionary> .\n"
        "<https://example.org/c/run/dictionary> prov:specializationOf d:scheme ; owl:versionInfo \"0.8\" .\n");
    const std::string q = query_file("old-dictionary-version.rq");
    const std::string scheme = "<https://w3id.org/geotex/dictionary/default/scheme>";
    CHECK(run_sparql(q, {data.path()}).rows ==
          Rows{{"a.ply", "<ni:///sha-256;AAAA>", scheme, "0.9", "1.0"},
               {"c.ply", "<https://example.org/c/mesh>", scheme, "0.8", "1.0"}});
    CHECK(run_sparql(edited(q, "BIND(\"\" AS ?given)", "BIND(\"0.9\" AS ?given)"), {data.path()})
              .rows == Rows{{"b.ply", "<ni:///sha-256;BBBB>", scheme, "1.0", "0.9"},
                            {"c.ply", "<https://example.org/c/mesh>", scheme, "0.8", "0.9"}});
}

TEST_CASE("run_sparql: computed doubles keep every digit", "[ontology][sparql]") {
    // Rasqal's own formatter writes these four as 9.03381848698E-2, 1.8067636973962E-1,
    // 3.0E-1 and 8.0E-2 (roqet shows it); ontology/sparql.cpp replaces it.
    const double a = 8.067636973961967e-2, b = 1.0000000000000002e-1;
    const TempFile data("doubles.ttl",
                        "<http://ex.org/a> <http://ex.org/v> \"8.067636973961967E-2\"^^<" + kXsd +
                            "double> .\n<http://ex.org/b> <http://ex.org/v> "
                            "\"1.0000000000000002E-1\"^^<" +
                            kXsd + "double> .\n");
    const QueryResult r = run_sparql(
        "SELECT (AVG(?v) AS ?mean) (SUM(?v) AS ?sum) (MAX(?v) * 3 AS ?triple) "
        "WHERE { ?s <http://ex.org/v> ?v }",
        {data.path()});
    REQUIRE(r.rows.size() == 1);
    CHECK(std::strtod(r.rows[0][0].c_str(), nullptr) == (a + b) / 2);
    CHECK(std::strtod(r.rows[0][1].c_str(), nullptr) == a + b);
    CHECK(std::strtod(r.rows[0][2].c_str(), nullptr) == b * 3);
    CHECK(r.terms[0][0] == "\"" + r.rows[0][0] + "\"^^<" + kXsd + "double>");
    // The shortest form: the data's own, for a value computed equal to it.
    CHECK(run_sparql("SELECT (MIN(?v) * 1 AS ?x) WHERE { ?s <http://ex.org/v> ?v }", {data.path()})
              .rows == Rows{{"8.067636973961967E-2"}});
}

// ---- several files, determinism -------------------------------------------------------

TEST_CASE("run_sparql: the union of several files is a set of triples", "[ontology][sparql]") {
    // Both fixtures hold the same dictionary: its triples count once.
    const std::string q =
        "PREFIX skos: <http://www.w3.org/2004/02/skos/core#>\n"
        "SELECT (COUNT(*) AS ?n) WHERE { ?c a skos:Concept }";
    CHECK(run_sparql(q, {kSample1}).rows == Rows{{"3"}});
    CHECK(run_sparql(q, {kSample1, kSample2}).rows == Rows{{"3"}});
    CHECK(run_sparql(q, {kSample1, kSample1}).rows == Rows{{"3"}});

    const std::string meshes =
        "PREFIX gtx: <https://w3id.org/geotex/ns#>\n"
        "PREFIX dcterms: <http://purl.org/dc/terms/>\n"
        "SELECT ?file WHERE { ?m a gtx:Mesh ; dcterms:identifier ?file } ORDER BY ?file";
    CHECK(run_sparql(meshes, {kSample1, kSample2}).rows == Rows{{kAmphora}, {"sphere-1.ply"}});

    SECTION("blank nodes of two files stay apart, N-Triples and RDF/XML by extension") {
        const TempFile a("a.ttl", "@prefix ex: <http://ex.org/> .\n_:b1 ex:p \"a\" .\n");
        const TempFile b("b.nt", "_:b1 <http://ex.org/p> \"b\" .\n");
        const TempFile c(
            "c.rdf",
            "<?xml version=\"1.0\"?>\n"
            "<rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\"\n"
            "         xmlns:ex=\"http://ex.org/\">\n"
            "  <rdf:Description rdf:about=\"http://ex.org/c\"><ex:p>c</ex:p></rdf:Description>\n"
            "</rdf:RDF>\n");
        const QueryResult r =
            run_sparql("SELECT (COUNT(DISTINCT ?s) AS ?n) WHERE { ?s <http://ex.org/p> ?o }",
                       {a.path(), b.path(), c.path()});
        CHECK(r.rows == Rows{{"3"}});
    }
    SECTION("no data file: an empty graph") {
        CHECK(run_sparql("SELECT ?s WHERE { ?s ?p ?o }", {}).rows.empty());
    }
}

TEST_CASE("run_sparql: the same rows on every run, with or without ORDER BY",
          "[ontology][sparql]") {
    std::vector<std::string> queries;
    for (const std::string& name : kQueryFiles) queries.push_back(query_file(name));
    queries.push_back(
        "PREFIX gtx: <https://w3id.org/geotex/ns#>\n"
        "SELECT ?texel ?texture ?n WHERE { ?texel gtx:inTexture ?texture ; gtx:faceCount ?n }");
    queries.push_back(
        "PREFIX gtx: <https://w3id.org/geotex/ns#>\n"
        "SELECT ?texture (COUNT(?texel) AS ?n) WHERE { ?texel gtx:inTexture ?texture } GROUP BY "
        "?texture");
    // (Not SELECT DISTINCT: Rasqal 0.9.33 leaks memory on it, which the sanitizer build
    // would report.)
    queries.push_back(
        "SELECT ?s ?t ?label WHERE { ?s a ?t OPTIONAL { ?s "
        "<http://www.w3.org/2000/01/rdf-schema#label> ?label } }");
    for (const std::string& q : queries) {
        const QueryResult first = run_sparql(q, {kSample1, kSample2});
        const QueryResult second = run_sparql(q, {kSample1, kSample2});
        CHECK_FALSE(first.rows.empty());
        CHECK(first.rows == second.rows);
        CHECK(first.terms == second.terms);
        CHECK(written(first, ResultFormat::Json) == written(second, ResultFormat::Json));
    }
}

// ---- ASK ------------------------------------------------------------------------------

TEST_CASE("run_sparql: ASK gives a boolean", "[ontology][sparql]") {
    const std::string ask =
        "PREFIX gtx: <https://w3id.org/geotex/ns#>\n"
        "ASK { ?texture gtx:texelCount 4 }";
    const QueryResult no = run_sparql(ask, {kSample1});
    CHECK(no.is_boolean);
    CHECK_FALSE(no.boolean_value);
    CHECK(no.variables.empty());
    CHECK(no.rows.empty());
    const QueryResult yes = run_sparql(ask, {kSample1, kSample2});
    CHECK(yes.is_boolean);
    CHECK(yes.boolean_value);

    CHECK(written(yes, ResultFormat::Table) == "true\n");
    CHECK(written(no, ResultFormat::Csv) == "_askResult\r\nfalse\r\n");
    const auto json = nlohmann::json::parse(written(yes, ResultFormat::Json));
    CHECK(json.at("boolean") == true);
    CHECK(json.at("head").is_object());
    CHECK_FALSE(json.contains("results"));
}

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
        {"SELECT * WHERE { ?s ?p ?o OPTIONAL { service SILENT <http://127.0.0.1:1/> { ?a ?b ?c } } }",
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
    CHECK_NOTHROW(run_sparql("PREFIX SERVICE: <http://ex.org/SERVICE>\n"
                             "# SERVICE <http://ex.org/>\n"
                             "SELECT ?s WHERE { ?s ?p ?o FILTER(?o != \"SERVICE <http://x/>\" && "
                             "?p != SERVICE:p) }",
                             {kSample1}));
    // LOAD and updates are no SPARQL query: refused at their keyword, before Rasqal parses.
    for (const auto& [update, column] :
         std::vector<std::pair<std::string, long>>{{"LOAD <file:///etc/passwd>", 1},
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
    CHECK_NOTHROW(run_sparql("PREFIX load: <http://ex.org/>\nSELECT ?delete WHERE { ?delete ?p "
                             "\"INSERT DATA\" }",
                             {kSample1}));
}

TEST_CASE("run_sparql: a query that runs past its timeout ends with QueryTimeout",
          "[ontology][sparql]") {
    // The issue's query: a four-way cross join over 200 triples, 1.6e9 rows, which runs for
    // hours; stopped at 0.3 s, it throws instead of returning the rows counted so far.
    std::string data;
    for (int i = 0; i < 200; ++i)
        data += "<http://ex.org/s" + std::to_string(i) + "> <http://ex.org/p" + std::to_string(i % 7) +
                "> \"v" + std::to_string(i) + "\" .\n";
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
    const QueryResult pairs =
        run_sparql("SELECT (COUNT(*) AS ?n) WHERE { ?a ?p ?o . ?b ?p2 ?o2 }", {file.path()}, params);
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
    const TempFile both("both.nt", "<http://ex.org/a> <http://ex.org/p> \"a\\u0000b\" .\n"
                                   "<http://ex.org/a> <http://ex.org/p> \"\xEF\xB7\x90\" .\n");
    CHECK_THROWS_AS(run_sparql("ASK {}", {both.path()}), geotex::InvalidInput);
}
