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

// ---- a small case built by hand: tests/annotation_case.hpp --------------------------------------

using SmallCase = test::SmallAnnotationCase;

}  // namespace

// ---- honest assertions (issue 15): what an annotation says of its target is true of it ------

namespace {

/// The honesty of an annotation graph, read back from the RDF alone (N-Triples of a document
/// with its dictionary): every concept's interval comes from its SHACL rule (sh:path, the
/// feature's shortcut property; sh:minInclusive, sh:maxExclusive), every texel value from its
/// shortcut triple. Returns the number of texel bodies checked.
int check_honest(const Parsed& p) {
    const std::string oa = "http://www.w3.org/ns/oa#";
    const std::string sh = "http://www.w3.org/ns/shacl#";
    const std::set<std::string> texels = p.subjects_of_type(kGtx + "Texel");
    const std::set<std::string> texel_annotations = p.subjects_of_type(kGtx + "TexelAnnotation");
    int checked = 0;
    for (const auto& t : p.triples) {
        if (t.p != oa + "hasTarget") continue;
        // A texture's concepts target the texture: no annotation of geotex but a texel
        // annotation targets a texel.
        if (texels.count(t.o)) {
            INFO(t.s << " targets the texel " << t.o);
            REQUIRE(texel_annotations.count(t.s) == 1);
            REQUIRE(p.find(t.s, kGtx + "describes").empty());
        } else {
            INFO(t.s << " targets " << t.o);
            REQUIRE(p.one(t.s, kGtx + "describes").o == t.o);
        }
    }
    const std::string prov = "http://www.w3.org/ns/prov#";
    const std::set<std::string> versions = p.subjects_of_type(kGtx + "DictionaryVersion");
    for (const std::string& a : texel_annotations) {
        const std::string texel = p.one(a, oa + "hasTarget").o;
        REQUIRE(texels.count(texel) == 1);
        const std::string orientation = p.one(texel, kGtx + "orientation").o;
        // The rule of a body is that of its interval in the dictionary version that the run
        // used: a store may hold several versions of the concept's interval.
        std::string version;
        for (const auto* used : p.find(p.one(a, prov + "wasGeneratedBy").o, prov + "used"))
            if (versions.count(used->o)) version = used->o;
        REQUIRE_FALSE(version.empty());
        for (const auto* body : p.find(a, oa + "hasBody")) {
            INFO(a << ": body " << body->o);
            std::string interval;
            for (const auto* of : p.find(body->o, kGtx + "hasInterval"))
                if (p.one(of->o, kGtx + "inVersion").o == version) interval = of->o;
            REQUIRE(p.one(interval, kGtx + "ofConcept").o == body->o);
            const std::string rule = p.one(interval, kGtx + "rule").o;
            const double value =
                std::strtod(p.one(texel, p.one(rule, sh + "path").o).o.c_str(), nullptr);
            for (const auto* lower : p.find(rule, sh + "minInclusive"))
                CHECK(value >= std::strtod(lower->o.c_str(), nullptr));
            for (const auto* upper : p.find(rule, sh + "maxExclusive"))
                CHECK(value < std::strtod(upper->o.c_str(), nullptr));
            for (const auto* relief : p.find(interval, kGtx + "appliesTo"))
                CHECK(relief->o == orientation);
            ++checked;
        }
    }
    return checked;
}

/// The bodies of the texel annotations, by texel IRI.
std::map<std::string, std::set<std::string>> texel_bodies(const Parsed& p) {
    std::map<std::string, std::set<std::string>> out;
    for (const std::string& a : p.subjects_of_type(kGtx + "TexelAnnotation"))
        for (const auto* body : p.find(a, "http://www.w3.org/ns/oa#hasBody"))
            out[p.one(a, "http://www.w3.org/ns/oa#hasTarget").o].insert(body->o);
    return out;
}

}  // namespace

TEST_CASE("write_annotation_rdf: every body is true of its target", "[ontology][rdf]") {
    SmallCase c;
    c.doc.include_dictionary = true;
    const std::string B = run_names(c.doc).base;
    const std::string ns = c.dictionary.namespace_iri;
    SECTION("the small case") {
        const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
        REQUIRE(p.errors.empty());
        CHECK(check_honest(p) == 5);
    }
    SECTION("a concept of the other relief is not said of a texel") {
        c.dictionary.concepts[4].relief = Relief::Engraved;  // large area, texel 2 is raised
        const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
        CHECK(texel_bodies(p)[B + "texel/2"] == std::set<std::string>{ns + "circular-shape"});
        CHECK(check_honest(p) == 4);
    }
    SECTION("a texel that no concept of its texture's facets holds for has no annotation") {
        c.seg.features.values(1, 7) = 0.5;  // texel 1 is no longer elongated
        const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
        CHECK(p.find(B + "texel/1/annotation", "http://www.w3.org/ns/oa#hasBody").empty());
        CHECK(p.find(B + "texel/1/annotation", kRdfType).empty());
        CHECK(check_honest(p) == 4);
    }
    SECTION("random texel values: exactly the concepts whose interval holds each value") {
        // Values drawn across every interval and the gaps between them (contour sphericity
        // has concepts below 0.05 only; area on both sides of 0.25; PCA variance 1 above 0.8).
        std::uint64_t state = 12345;
        const auto uniform = [&state](double lo, double hi) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1.0p-53;
        };
        for (int round = 0; round < 50; ++round) {
            INFO("round " << round);
            for (int i = 0; i < 3; ++i) {
                c.seg.features.values(i, 1) = uniform(0, 0.1);
                c.seg.features.values(i, 4) = uniform(-0.1, 0.5);
                c.seg.features.values(i, 7) = uniform(0.6, 1);
            }
            const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
            REQUIRE(p.errors.empty());
            check_honest(p);
            // And nothing true is left out: the expected bodies computed here from the values.
            std::map<std::string, std::set<std::string>> expected;
            const auto add = [&](int i, const char* id) {
                expected[B + "texel/" + std::to_string(i)].insert(ns + id);
            };
            for (int i : {0, 2}) {
                if (c.seg.features.values(i, 1) < 0.05) add(i, "circular-shape");
                const double area = c.seg.features.values(i, 4);
                if (area >= 0 && area < 0.25) add(i, "small-area");
                if (area >= 0.25) add(i, "large-area");
            }
            if (c.seg.features.values(1, 7) >= 0.8) add(1, "elongated");
            CHECK(texel_bodies(p) == expected);
        }
    }
}
