#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "ontology/rdf_writer.hpp"
#include "tests/annotation_case.hpp"
#include "tests/rdf_readback.hpp"

using namespace geotex;
using namespace geotex::test;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- a small case built by hand: tests/annotation_case.hpp --------------------------------------

using SmallCase = test::SmallAnnotationCase;

}  // namespace
TEST_CASE("write_dictionary_rdf: SKOS concepts, their intervals in this version, SHACL rules",
          "[ontology][rdf]") {
    SmallCase c;
    const std::string ttl = dictionary_rdf(c.dictionary, RdfFormat::Turtle);
    const Parsed p = parse_rdf(ttl, "turtle");
    REQUIRE(p.errors.empty());
    CHECK(p.blank_nodes == 0);
    CHECK(p.triples.size() ==
          parse_rdf(dictionary_rdf(c.dictionary, RdfFormat::NTriples), "ntriples").triples.size());
    const std::string ns = c.dictionary.namespace_iri;
    const std::string skos = "http://www.w3.org/2004/02/skos/core#";
    const std::string sh = "http://www.w3.org/ns/shacl#";
    const std::string scheme = ns + "scheme", version = ns + "scheme/version/1.0";
    // 5 concepts and 4 facets, which are top concepts
    CHECK(p.subjects_of_type(skos + "Concept").size() == c.dictionary.concepts.size() + 4);
    CHECK(p.subjects_of_type(kGtx + "ConceptInterval").size() == c.dictionary.concepts.size());
    CHECK(p.subjects_of_type(skos + "ConceptScheme") == std::set<std::string>{scheme});
    CHECK(p.subjects_of_type(sh + "PropertyShape").size() == c.dictionary.concepts.size());

    // The version node carries what changes from one version to the next; the scheme only
    // what stays.
    CHECK(p.subjects_of_type(kGtx + "DictionaryVersion") == std::set<std::string>{version});
    CHECK(p.one(scheme, "http://purl.org/dc/terms/hasVersion").o == version);
    CHECK(p.one(version, "http://purl.org/dc/terms/isVersionOf").o == scheme);
    CHECK(p.one(version, "http://www.w3.org/ns/prov#specializationOf").o == scheme);
    CHECK(p.one(version, "http://www.w3.org/2002/07/owl#versionInfo").o == "1.0");
    CHECK(p.one(version, kGtx + "sha256").o == c.dictionary.sha256);
    CHECK(p.find(scheme, kGtx + "sha256").empty());
    CHECK(p.find(scheme, "http://www.w3.org/2002/07/owl#versionInfo").empty());

    // Bounds, relief, definition and source on the interval node, canonical decimals of the
    // YAML text; infinite bounds absent.
    const std::string small = version + "/small-area";
    CHECK(p.one(ns + "small-area", kGtx + "hasInterval").o == small);
    CHECK(p.one(small, kGtx + "ofConcept").o == ns + "small-area");
    CHECK(p.one(small, kGtx + "inVersion").o == version);
    const auto& upper = p.one(small, kGtx + "upperBound");
    CHECK(upper.o == "0.25");
    CHECK(upper.datatype == kXsd + "decimal");
    CHECK(p.one(small, kGtx + "lowerBound").o == "0.0");
    CHECK(p.find(ns + "small-area", kGtx + "lowerBound").empty());
    CHECK(p.one(version + "/elongated", kGtx + "lowerBound").o == "0.8");
    CHECK(p.find(version + "/elongated", kGtx + "upperBound").empty());
    CHECK(p.find(version + "/circular-shape", kGtx + "lowerBound").empty());
    CHECK(p.one(version + "/flat", kGtx + "upperBound").o == "0.001");  // no text: the double
    const std::string circular = version + "/circular-shape";
    CHECK(p.one(circular, skos + "definition").o == "The contour stays close to a circle.");
    CHECK(p.one(circular, "http://purl.org/dc/terms/source").o == "paper, Table 3");
    CHECK(p.find(ns + "circular-shape", skos + "definition").empty());
    const std::string rule = circular + "/rule";
    CHECK(p.one(circular, kGtx + "rule").o == rule);
    CHECK(p.find(ns + "circular-shape", kGtx + "rule").empty());
    CHECK(p.one(rule, sh + "path").o == kGtx + "contourSphericity");
    CHECK(p.one(rule, sh + "maxExclusive").o == "0.05");
    CHECK(p.find(rule, sh + "minInclusive").empty());
    CHECK(p.one(ns + "circular-shape", kGtx + "onFeature").o == kGtx + "contour_sphericity");
}

TEST_CASE("write_dictionary_rdf: scheme metadata, matches and the date of the version",
          "[ontology][rdf]") {
    SmallCase c;
    Dictionary& d = c.dictionary;
    const std::string ns = d.namespace_iri, dcterms = "http://purl.org/dc/terms/";
    const std::string skos = "http://www.w3.org/2004/02/skos/core#";
    const std::string aat = "http://vocab.getty.edu/aat/";
    {
        // None given: none written.
        const Parsed p = parse_rdf(dictionary_rdf(d, RdfFormat::NTriples), "ntriples");
        CHECK(p.find(ns + "scheme", dcterms + "creator").empty());
        CHECK(p.find(ns + "scheme", dcterms + "license").empty());
        CHECK(p.find(ns + "scheme/version/1.0", dcterms + "modified").empty());
        CHECK(p.find(ns + "circular-shape", skos + "exactMatch").empty());
    }
    d.creators = {"https://w3id.org/geotex/", "https://orcid.org/0000-0000-0000-0000"};
    d.license = "https://creativecommons.org/licenses/by/4.0/";
    d.modified = "2026-12-01";
    d.concepts[0].exact_matches = {aat + "1"};
    d.concepts[0].close_matches = {aat + "2", aat + "3"};
    const Parsed p = parse_rdf(dictionary_rdf(d, RdfFormat::Turtle), "turtle");
    REQUIRE(p.errors.empty());
    std::set<std::string> creators;
    for (const auto* t : p.find(ns + "scheme", dcterms + "creator")) creators.insert(t->o);
    CHECK(creators == std::set<std::string>(d.creators.begin(), d.creators.end()));
    CHECK(p.one(ns + "scheme", dcterms + "license").o == d.license);
    const auto& modified = p.one(ns + "scheme/version/1.0", dcterms + "modified");
    CHECK(modified.o == "2026-12-01");
    CHECK(modified.datatype == kXsd + "date");
    CHECK(p.find(ns + "scheme", dcterms + "modified").empty());
    CHECK(p.one(ns + "circular-shape", skos + "exactMatch").o == aat + "1");
    std::set<std::string> close;
    for (const auto* t : p.find(ns + "circular-shape", skos + "closeMatch")) close.insert(t->o);
    CHECK(close == std::set<std::string>{aat + "2", aat + "3"});

    // What a dictionary built by hand may hold that the YAML checker refuses.
    std::ostringstream out;
    SECTION("creator not absolute") { d.creators = {"geotex"}; }
    SECTION("licence with a space") { d.license = "https://example.org/a licence"; }
    SECTION("match with a dot segment") { d.concepts[1].close_matches = {aat + "x/../1"}; }
    SECTION("date that does not exist") { d.modified = "2026-02-30"; }
    SECTION("date with a time") { d.modified = "2026-12-01T00:00:00Z"; }
    SECTION("no version") { d.version.clear(); }
    REQUIRE_THROWS_AS(write_dictionary_rdf(out, d, RdfFormat::Turtle), InvalidInput);
    CHECK(out.str().empty());
}

TEST_CASE("write_dictionary_rdf: preconditions", "[ontology][rdf]") {
    SmallCase c;
    Dictionary& d = c.dictionary;
    std::ostringstream out;
    SECTION("namespace without trailing / or #") { d.namespace_iri = "https://example.org/dict"; }
    SECTION("namespace with a space") { d.namespace_iri = "https://example.org/my dict/"; }
    SECTION("bad language tag") { d.concepts[1].labels["en fr"] = "x"; }
    SECTION("bad title language") { d.titles["-"] = "x"; }
    SECTION("bound text that is not its value") { d.concepts[1].upper_text = "0.5"; }
    SECTION("bound text that is no number") { d.concepts[1].upper_text = "0.25m"; }
    SECTION("NaN bound") { d.concepts[1].lower = kNaN; }
    SECTION("feature out of range") { d.concepts[1].feature = kNumFeatures; }
    SECTION("duplicate id") { d.concepts[1].id = d.concepts[0].id; }
    SECTION("empty id") { d.concepts[1].id.clear(); }
    SECTION("bad digest") { d.sha256 = "not a digest"; }
    SECTION("control character in a definition") { d.concepts[0].definitions["en"] = "a\x1B[31m"; }
    SECTION("facet feature out of range") { d.facets[2].features = {kNumFeatures}; }
    SECTION("facet without id") { d.facets[0].id.clear(); }
    REQUIRE_THROWS_AS(write_dictionary_rdf(out, d, RdfFormat::Turtle), InvalidInput);
    CHECK(out.str().empty());
}

TEST_CASE("write_dictionary_rdf: bounds written as canonical decimals", "[ontology][rdf]") {
    SmallCase c;
    const std::string ns = c.dictionary.namespace_iri;
    auto& b = c.dictionary.concepts[2];  // elongated, [lower, +inf)
    const auto lower_of = [&](const std::string& text, double value) {
        b.lower_text = text;
        b.lower = value;
        const Parsed p = parse_rdf(dictionary_rdf(c.dictionary, RdfFormat::Turtle), "turtle");
        REQUIRE(p.errors.empty());
        const auto& t = p.one(ns + "scheme/version/1.0/elongated", kGtx + "lowerBound");
        CHECK(t.datatype == kXsd + "decimal");
        return t.o;
    };
    CHECK(lower_of("5", 5) == "5.0");
    CHECK(lower_of("5.", 5) == "5.0");
    CHECK(lower_of("+0.50", 0.5) == "0.5");
    CHECK(lower_of("-0", -0.0) == "0.0");
    CHECK(lower_of("-1.5E+2", -150) == "-150.0");
    CHECK(lower_of("12.5e-3", 0.0125) == "0.0125");
    CHECK(lower_of("0.1", 0.1) == "0.1");
    CHECK(lower_of("", 0.1) == "0.1");
    CHECK(lower_of("", 1e21) == "1000000000000000000000.0");
    CHECK(lower_of("", -2.5e-8) == "-0.000000025");
}

TEST_CASE("write_dictionary_rdf: facets are top concepts, broader than their concepts",
          "[ontology][rdf]") {
    SmallCase c;
    const std::string ns = c.dictionary.namespace_iri;
    const std::string skos = "http://www.w3.org/2004/02/skos/core#";
    const Parsed p = parse_rdf(dictionary_rdf(c.dictionary, RdfFormat::NTriples), "ntriples");
    REQUIRE(p.errors.empty());
    const std::string size = ns + "scheme/facet/size";
    // SKOS makes Concept and Collection disjoint: a facet is a concept, not a collection.
    CHECK(p.subjects_of_type(skos + "Collection").empty());
    CHECK(p.subjects_of_type(kGtx + "Facet").size() == 4);
    CHECK(p.subjects_of_type(skos + "Concept").count(size) == 1);
    std::map<std::string, std::string> labels;
    for (const auto* t : p.find(size, skos + "prefLabel")) labels[t->language] = t->o;
    CHECK(labels == std::map<std::string, std::string>{{"en", "size"}, {"fr", "taille"}});
    CHECK(p.one(size, skos + "notation").o == "size");
    CHECK(p.one(size, kGtx + "coversFeature").o == kGtx + "area");
    CHECK(p.one(size, skos + "topConceptOf").o == ns + "scheme");
    CHECK(p.one(size, skos + "inScheme").o == ns + "scheme");
    std::set<std::string> top;
    for (const auto* t : p.find(ns + "scheme", skos + "hasTopConcept")) top.insert(t->o);
    CHECK(top == p.subjects_of_type(kGtx + "Facet"));
    std::set<std::string> narrower;
    for (const auto* t : p.find(size, skos + "narrower")) narrower.insert(t->o);
    CHECK(narrower == std::set<std::string>{ns + "small-area", ns + "large-area"});
    CHECK(p.find(size, skos + "member").empty());
    for (const auto& concept_ : c.dictionary.concepts) {
        INFO(concept_.id);
        const std::string broader = p.one(ns + concept_.id, skos + "broader").o;
        CHECK(p.subjects_of_type(kGtx + "Facet").count(broader) == 1);
    }
    // Relief: only the engraving word says so, on its interval.
    const std::string version = ns + "scheme/version/1.0/";
    CHECK(p.one(version + "elongated", kGtx + "appliesTo").o == kGtx + "NegativeDetails");
    CHECK(p.find(version + "circular-shape", kGtx + "appliesTo").empty());
    c.dictionary.concepts[0].relief = Relief::Raised;
    const Parsed raised = parse_rdf(dictionary_rdf(c.dictionary, RdfFormat::NTriples), "ntriples");
    CHECK(raised.one(version + "circular-shape", kGtx + "appliesTo").o == kGtx + "PositiveDetails");

    // Two facets with one id would be one node.
    c.dictionary.facets[1].id = "outline";
    std::ostringstream out;
    REQUIRE_THROWS_AS(write_dictionary_rdf(out, c.dictionary, RdfFormat::Turtle), InvalidInput);
    CHECK(out.str().empty());
}

TEST_CASE("write_dictionary_rdf: a dictionary without facets has one per feature, written alike",
          "[ontology][rdf]") {
    const std::string yaml =
        "scheme:\n  id: old\n  version: \"0.9\"\n  namespace: \"https://example.org/old/\"\n"
        "  languages: [en]\n  title: {en: Old}\nfeatures:\n  area:\n"
        "    - id: small-area\n      interval: [0, 0.1]\n      labels: {en: small area}\n"
        "    - id: large-area\n      interval: [0.5, .inf]\n      labels: {en: large area}\n"
        "  contour_sphericity:\n    - id: circular-shape\n      interval: [0, 0.05]\n"
        "      labels: {en: circular shape}\n";
    const Dictionary d = parse_dictionary(yaml, "old.yaml");
    REQUIRE_FALSE(d.declares_facets);
    const std::string ns = "https://example.org/old/";
    const std::string skos = "http://www.w3.org/2004/02/skos/core#";
    const Parsed p = parse_rdf(dictionary_rdf(d, RdfFormat::NTriples), "ntriples");
    REQUIRE(p.errors.empty());
    CHECK(p.subjects_of_type(kGtx + "Facet") ==
          std::set<std::string>{ns + "scheme/facet/area", ns + "scheme/facet/contour_sphericity"});
    CHECK(p.one(ns + "scheme/facet/area", skos + "prefLabel").o == "area");
    CHECK(p.one(ns + "small-area", skos + "broader").o == ns + "scheme/facet/area");
    CHECK(p.one(ns + "circular-shape", skos + "broader").o ==
          ns + "scheme/facet/contour_sphericity");
    CHECK(p.find(ns + "scheme", skos + "hasTopConcept").size() == 2);

    // Built by hand without any facet: the same one-feature facets, labelled in the
    // dictionary's languages.
    SmallCase c;
    c.dictionary.facets.clear();
    c.dictionary.declares_facets = false;
    const std::string demo = c.dictionary.namespace_iri;
    const Parsed q = parse_rdf(dictionary_rdf(c.dictionary, RdfFormat::NTriples), "ntriples");
    REQUIRE(q.errors.empty());
    CHECK(q.subjects_of_type(kGtx + "Facet").size() == 4);
    CHECK(q.one(demo + "small-area", skos + "broader").o == demo + "scheme/facet/area");
    CHECK(q.one(demo + "large-area", skos + "broader").o == demo + "scheme/facet/area");
    CHECK(q.find(demo + "scheme/facet/area", skos + "prefLabel").size() == 2);
}

TEST_CASE("write_dictionary_rdf: two versions in one graph, one concept with two intervals",
          "[ontology][rdf][versions]") {
    // Version 1.1 narrows one interval (small area [0, 0.25) -> [0, 0.2)); the union of both
    // outputs is what a store holding runs of both versions holds.
    SmallCase c;
    const std::string v10 = dictionary_rdf(c.dictionary, RdfFormat::NTriples);
    Dictionary& d = c.dictionary;
    d.version = "1.1";
    d.sha256 = "60303ae22b998861bce3b28f33eec1be758a213c86c93c076dbe9f558c11c752";
    d.concepts[1].upper = 0.2;
    d.concepts[1].upper_text = "0.2";
    const std::string v11 = dictionary_rdf(d, RdfFormat::NTriples);
    const Parsed p = parse_rdf(v10 + v11, "ntriples");
    REQUIRE(p.errors.empty());
    const std::string ns = d.namespace_iri, scheme = ns + "scheme";
    const std::string skos = "http://www.w3.org/2004/02/skos/core#";

    // One scheme with two versions; the concept IRIs are the same in both.
    CHECK(p.subjects_of_type(skos + "ConceptScheme") == std::set<std::string>{scheme});
    CHECK(p.subjects_of_type(kGtx + "DictionaryVersion") ==
          std::set<std::string>{scheme + "/version/1.0", scheme + "/version/1.1"});
    CHECK(p.find(scheme, "http://purl.org/dc/terms/hasVersion").size() == 2);
    std::set<std::string> concepts;
    for (const auto& t : p.triples)
        if (t.p == kGtx + "onFeature") concepts.insert(t.s);
    CHECK(concepts.size() == d.concepts.size());
    for (const auto& concept_ : d.concepts) CHECK(concepts.count(ns + concept_.id) == 1);

    // The narrowed concept: two interval nodes, each with one bound of each kind, its own.
    std::map<std::string, std::string> upper_by_version;
    for (const auto* t : p.find(ns + "small-area", kGtx + "hasInterval")) {
        const auto uppers = p.find(t->o, kGtx + "upperBound");
        REQUIRE(uppers.size() == 1);
        CHECK(p.find(t->o, kGtx + "lowerBound").size() == 1);
        CHECK(p.find(t->o + "/rule", "http://www.w3.org/ns/shacl#maxExclusive").size() == 1);
        upper_by_version[p.one(t->o, kGtx + "inVersion").o] = uppers.front()->o;
    }
    CHECK(upper_by_version == std::map<std::string, std::string>{{scheme + "/version/1.0", "0.25"},
                                                                 {scheme + "/version/1.1", "0.2"}});

    // SKOS integrity: every concept, facets included, and the scheme have one prefLabel per
    // language (the triples of both versions are the same ones). Top concepts and broader
    // are there, once.
    std::map<std::pair<std::string, std::string>, std::set<std::string>> labels;
    for (const auto& t : p.triples)
        if (t.p == skos + "prefLabel") labels[{t.s, t.language}].insert(t.o);
    CHECK(labels.size() == (d.concepts.size() + d.facets.size() + 1) * 2);
    for (const auto& [key, values] : labels) {
        INFO(key.first << " @" << key.second);
        CHECK(values.size() == 1);
    }
    std::set<std::string> top;
    for (const auto* t : p.find(scheme, skos + "hasTopConcept")) top.insert(t->o);
    CHECK(top.size() == d.facets.size());
    for (const auto& concept_ : d.concepts) {
        std::set<std::string> broader;
        for (const auto* t : p.find(ns + concept_.id, skos + "broader")) broader.insert(t->o);
        REQUIRE(broader.size() == 1);
        CHECK(top.count(*broader.begin()) == 1);
    }
    // A version's own metadata stays on its node.
    CHECK(p.one(scheme + "/version/1.1", kGtx + "sha256").o == d.sha256);
    CHECK(p.find(scheme, kGtx + "sha256").empty());
}
