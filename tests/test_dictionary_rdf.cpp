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
#include "geometry/errors.hpp"
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
TEST_CASE("write_dictionary_rdf: SKOS concepts with decimal bounds and SHACL rules",
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
    CHECK(p.subjects_of_type(skos + "Concept").size() == c.dictionary.concepts.size());
    CHECK(p.subjects_of_type(skos + "ConceptScheme") == std::set<std::string>{ns + "scheme"});
    CHECK(p.subjects_of_type(sh + "PropertyShape").size() == c.dictionary.concepts.size());
    CHECK(p.one(ns + "scheme", kGtx + "sha256").o == c.dictionary.sha256);

    // Bounds: canonical decimals of the YAML text; infinite bounds absent.
    const auto& upper = p.one(ns + "small-area", kGtx + "upperBound");
    CHECK(upper.o == "0.25");
    CHECK(upper.datatype == kXsd + "decimal");
    CHECK(p.one(ns + "small-area", kGtx + "lowerBound").o == "0.0");
    CHECK(p.one(ns + "elongated", kGtx + "lowerBound").o == "0.8");
    CHECK(p.find(ns + "elongated", kGtx + "upperBound").empty());
    CHECK(p.find(ns + "circular-shape", kGtx + "lowerBound").empty());
    CHECK(p.one(ns + "flat", kGtx + "upperBound").o == "0.001");  // no text: from the double
    const std::string rule = ns + "circular-shape/rule";
    CHECK(p.one(ns + "circular-shape", kGtx + "rule").o == rule);
    CHECK(p.one(rule, sh + "path").o == kGtx + "contourSphericity");
    CHECK(p.one(rule, sh + "maxExclusive").o == "0.05");
    CHECK(p.find(rule, sh + "minInclusive").empty());
    CHECK(p.one(ns + "circular-shape", kGtx + "onFeature").o == kGtx + "contour_sphericity");
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
        const auto& t = p.one(ns + "elongated", kGtx + "lowerBound");
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

TEST_CASE("write_annotation_rdf: the dictionary's facets and reliefs in SKOS", "[ontology][rdf]") {
    SmallCase c;
    const std::string ns = c.dictionary.namespace_iri;
    const std::string skos = "http://www.w3.org/2004/02/skos/core#";
    const Parsed p = parse_rdf(dictionary_rdf(c.dictionary, RdfFormat::NTriples), "ntriples");
    REQUIRE(p.errors.empty());
    const std::string size = ns + "scheme/facet/size";
    CHECK(p.subjects_of_type(skos + "Collection").size() == 4);
    CHECK(p.subjects_of_type(kGtx + "Facet").count(size) == 1);
    std::map<std::string, std::string> labels;
    for (const auto* t : p.find(size, skos + "prefLabel")) labels[t->language] = t->o;
    CHECK(labels == std::map<std::string, std::string>{{"en", "size"}, {"fr", "taille"}});
    CHECK(p.one(size, skos + "notation").o == "size");
    CHECK(p.one(size, kGtx + "coversFeature").o == kGtx + "area");
    std::set<std::string> members;
    for (const auto* t : p.find(size, skos + "member")) members.insert(t->o);
    CHECK(members == std::set<std::string>{ns + "small-area", ns + "large-area"});
    // Relief: only the engraving word says so.
    CHECK(p.one(ns + "elongated", kGtx + "appliesTo").o == kGtx + "NegativeDetails");
    CHECK(p.find(ns + "circular-shape", kGtx + "appliesTo").empty());
    c.dictionary.concepts[0].relief = Relief::Raised;
    const Parsed raised = parse_rdf(dictionary_rdf(c.dictionary, RdfFormat::NTriples), "ntriples");
    CHECK(raised.one(ns + "circular-shape", kGtx + "appliesTo").o == kGtx + "PositiveDetails");

    // A dictionary without `facets:` (each feature its own facet) writes none.
    c.dictionary.declares_facets = false;
    const Parsed implicit = parse_rdf(dictionary_rdf(c.dictionary, RdfFormat::NTriples), "ntriples");
    CHECK(implicit.subjects_of_type(skos + "Collection").empty());
    // 4 facets of 6 triples (2 types, 2 labels, notation, feature) and 5 members; + appliesTo.
    CHECK(implicit.triples.size() + 4 * 6 + 5 == p.triples.size() + 1);

    // Two facets with one id would be one node.
    c.dictionary.declares_facets = true;
    c.dictionary.facets[1].id = "outline";
    std::ostringstream out;
    REQUIRE_THROWS_AS(write_dictionary_rdf(out, c.dictionary, RdfFormat::Turtle), InvalidInput);
    CHECK(out.str().empty());
}
