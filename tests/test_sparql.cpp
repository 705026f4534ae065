// Tests of the embedded SPARQL (ontology/sparql.cpp): the documented queries of
// ontology/queries/ on the hand-written fixtures tests/data/annotation-sample*.ttl, and what
// the engine promises of any query (sets of triples, stable rows, ASK).

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "tests/sparql_test_support.hpp"

using namespace geotex::sparql_test;

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

TEST_CASE(
    "run_sparql: old-dictionary-version.rq, with the version nodes of before and after "
    "issue 16",
    "[ontology][sparql]") {
    // a.ply and b.ply: runs that use the shared version node N scheme/version/<v> (issue 16);
    // c.ply: a run with its own B run/dictionary node (before). No IRI prefix is shared.
    const TempFile data("versions.ttl",
                        "@prefix gtx: <https://w3id.org/geotex/ns#> .\n"
                        "@prefix prov: <http://www.w3.org/ns/prov#> .\n"
                        "@prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
                        "@prefix dcterms: <http://purl.org/dc/terms/> .\n"
                        "@prefix d: <https://w3id.org/geotex/dictionary/default/> .\n"
                        "<ni:///sha-256;AAAA> a gtx:Mesh ; dcterms:identifier \"a.ply\" .\n"
                        "<ni:///sha-256;BBBB> a gtx:Mesh ; dcterms:identifier \"b.ply\" .\n"
                        "<ni:///sha-256;KKKA#run> a gtx:TextureAnalysis ;\n"
                        "    prov:used <ni:///sha-256;AAAA>, "
                        "<https://w3id.org/geotex/dictionary/default/scheme/version/0.9> .\n"
                        "<ni:///sha-256;KKKB#run> a gtx:TextureAnalysis ;\n"
                        "    prov:used <ni:///sha-256;BBBB>, "
                        "<https://w3id.org/geotex/dictionary/default/scheme/version/1.0> .\n"
                        "<https://w3id.org/geotex/dictionary/default/scheme/version/0.9> a "
                        "gtx:DictionaryVersion, prov:Entity ;\n"
                        "    dcterms:isVersionOf d:scheme ; prov:specializationOf d:scheme ; "
                        "owl:versionInfo \"0.9\" .\n"
                        "<https://w3id.org/geotex/dictionary/default/scheme/version/1.0> a "
                        "gtx:DictionaryVersion, prov:Entity ;\n"
                        "    dcterms:isVersionOf d:scheme ; prov:specializationOf d:scheme ; "
                        "owl:versionInfo \"1.0\" .\n"
                        "d:scheme dcterms:hasVersion "
                        "<https://w3id.org/geotex/dictionary/default/scheme/version/0.9>,\n"
                        "    <https://w3id.org/geotex/dictionary/default/scheme/version/1.0> .\n"
                        "<https://example.org/c/mesh> a gtx:Mesh ; dcterms:identifier \"c.ply\" .\n"
                        "<https://example.org/c/run> a gtx:TextureAnalysis ;\n"
                        "    prov:used <https://example.org/c/mesh>, d:scheme, "
                        "<https://example.org/c/run/dictionary> .\n"
                        "<https://example.org/c/run/dictionary> prov:specializationOf d:scheme ; "
                        "owl:versionInfo \"0.8\" .\n");
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
