// The names of a run and what joins it to a museum's graph (ontology/README.md, "IRIs",
// "The bridge", "Units"): run-unique, stable IRIs; the CIDOC-CRM and Linked Art bridge;
// lengths and areas in the mesh's unit; who made the annotations.

#include <catch2/catch.hpp>
#include <set>
#include <string>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "ontology/rdf_writer.hpp"
#include "tests/annotation_case.hpp"
#include "tests/rdf_readback.hpp"

using namespace geotex;
using namespace geotex::test;

namespace {

const std::string kCrm = "http://www.cidoc-crm.org/cidoc-crm/";
const std::string kQudt = "http://qudt.org/schema/qudt/";
const std::string kUnit = "http://qudt.org/vocab/unit/";
const std::string kDcterms = "http://purl.org/dc/terms/";

/// The subjects of the union of two outputs that both describe.
std::set<std::string> shared_subjects(const Parsed& a, const Parsed& b) {
    std::set<std::string> sa, out;
    for (const auto& t : a.triples) sa.insert(t.s);
    for (const auto& t : b.triples)
        if (sa.count(t.s)) out.insert(t.s);
    return out;
}

}  // namespace

TEST_CASE("ni_name: the RFC 6920 hash name of a SHA-256 digest", "[ontology][iri]") {
    // RFC 6920 section 8.1's example, the digest of "Hello World!" (base64url by Python).
    CHECK(ni_name(sha256_hex("Hello World!")) ==
          "ni:///sha-256;f4OxZX_x_FO5LcGBSKHWXfwtSx-j1ncoSt3SABJtkGk");
    CHECK(ni_name(kMeshDigest) == "ni:///sha-256;47DEQpj8HBSa-_TImW-5JCeuQeRkm5NMpJWZG3hSuFU");
    CHECK(ni_name(std::string(64, 'F')) == ni_name(std::string(64, 'f')));
    CHECK_THROWS_AS(ni_name("abc"), InvalidInput);
    CHECK_THROWS_WITH(ni_name(std::string(63, '0') + "g"), Catch::Contains("position 63"));
}

TEST_CASE("run_names: the default names are hash names, unique per run, stable for the same run",
          "[ontology][iri]") {
    SmallAnnotationCase c;
    c.doc.base_iri.clear();
    const RunNames names = run_names(c.doc);
    CHECK(names.key.size() == 64);
    CHECK(names.mesh == ni_name(kMeshDigest));
    CHECK(names.base == ni_name(names.key) + "#");
    CHECK(run_names(c.doc).base == names.base);  // the same document, the same names

    // Any option, the dictionary, the version, the unit, the creator: another run.
    std::set<std::string> bases{names.base};
    const auto another = [&](const char* what) {
        INFO(what);
        const RunNames other = run_names(c.doc);
        CHECK(other.mesh == names.mesh);  // the mesh keeps its one IRI
        CHECK(bases.insert(other.base).second);
    };
    c.doc.params.radius_rel = 0.06;
    another("scale");
    c.doc.description.min_agreement = 0.8;
    another("an annotation option");
    c.dictionary.sha256 = std::string(64, 'a');
    another("the dictionary");
    c.doc.software_version = "9.9.9";
    another("the geotex version");
    c.doc.mesh_unit = MeshUnit::Millimetre;
    another("the mesh unit");
    c.doc.creator_iri = "https://museum.example.org/staff/7";
    another("the creator");
    // The object is said of the mesh, not of the run.
    const std::string before_object = run_names(c.doc).base;
    c.doc.object_iri = "https://museum.example.org/object/42";
    CHECK(run_names(c.doc).base == before_object);

    // With a base: the mesh under it, the run's nodes under B run/<first 32 hex digits>/.
    c.doc.base_iri = "https://museum.example.org/scan/42/";
    const RunNames based = run_names(c.doc);
    CHECK(based.mesh == "https://museum.example.org/scan/42/mesh");
    CHECK(based.base == "https://museum.example.org/scan/42/run/" + based.key.substr(0, 32) + "/");
}

TEST_CASE("write_annotation_rdf: two runs of one mesh share the mesh node only",
          "[ontology][iri]") {
    SmallAnnotationCase c;
    c.doc.base_iri.clear();
    const Parsed at4 = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    const RunNames names4 = run_names(c.doc);
    c.doc.params.radius_rel = 0.06;
    const Parsed at6 = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    REQUIRE(at4.errors.empty());
    REQUIRE(at6.errors.empty());
    // What both describe: the mesh (with the same triples), geotex's release and the version
    // of the dictionary; no texel, texture, measurement or annotation gets a second value.
    const std::string software = software_iri(c.doc.software_version);
    const std::string version = c.dictionary.namespace_iri + "scheme/version/1.0";
    CHECK(shared_subjects(at4, at6) ==
          std::set<std::string>{ni_name(kMeshDigest), software, version});
    CHECK(at4.find(ni_name(kMeshDigest), kGtx + "faceCount").size() == 1);
    CHECK(at4.one(names4.base + "run", kGtx + "runKey").o == names4.key);
    CHECK(at6.one(run_names(c.doc).base + "run", kGtx + "runKey").o == run_names(c.doc).key);
    CHECK(names4.key != run_names(c.doc).key);
}

TEST_CASE("write_annotation_rdf: the mesh represents the object (CIDOC-CRM, Linked Art)",
          "[ontology][bridge]") {
    SmallAnnotationCase c;
    const std::string object = "https://museum.example.org/object/42";
    const std::string mesh = run_names(c.doc).mesh;
    const Parsed plain = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    CHECK(plain.find(mesh, kCrm + "P138_represents").empty());
    // A PLY has no registered media type: the format is geotex's own name only.
    CHECK(plain.find(mesh, "http://purl.org/dc/elements/1.1/format").empty());
    CHECK(plain.one(mesh, kGtx + "fileFormat").o == c.doc.mesh_format);

    c.doc.object_iri = object;
    c.doc.mesh_format = "obj";
    const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::Turtle), "turtle");
    REQUIRE(p.errors.empty());
    CHECK(p.one(mesh, kCrm + "P138_represents").o == object);
    CHECK(p.subjects_of_type("http://www.ics.forth.gr/isl/CRMdig/D1_Digital_Object") ==
          std::set<std::string>{mesh});
    const std::string visual = p.one(mesh, "https://linked.art/ns/terms/digitally_shows").o;
    CHECK(visual == mesh + "/visual-item");
    CHECK(p.subjects_of_type(kCrm + "E36_Visual_Item") == std::set<std::string>{visual});
    CHECK(p.one(visual, kCrm + "P138_represents").o == object);
    CHECK(p.one(object, kCrm + "P138i_has_representation").o == visual);
    CHECK(p.one(mesh, "http://purl.org/dc/elements/1.1/format").o == "model/obj");

    SECTION("IRIs that are not absolute, or hold spaces, quotes or angle brackets") {
        for (const char* bad : {"museum/object/42", "https://m.example.org/a b",
                                "https://m.example.org/\"x\"", "https://m.example.org/<x>", ""}) {
            INFO(bad);
            c.doc.object_iri = bad;
            if (std::string(bad).empty()) continue;  // empty: no object
            CHECK_THROWS_AS(annotation(c.doc, RdfFormat::Turtle), InvalidInput);
            c.doc.object_iri = object;
            c.doc.creator_iri = bad;
            CHECK_THROWS_AS(annotation(c.doc, RdfFormat::Turtle), InvalidInput);
            c.doc.creator_iri.clear();
        }
    }
}

TEST_CASE("write_annotation_rdf: lengths and areas in the mesh unit, with QUDT units",
          "[ontology][units]") {
    SmallAnnotationCase c;  // unit_scale 1/8: the largest side is 8 mesh units
    const Parsed plain = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    CHECK(plain.subjects_of_type(kQudt + "QuantityValue").empty());

    c.doc.mesh_unit = MeshUnit::Millimetre;
    const RunNames names = run_names(c.doc);
    const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    REQUIRE(p.errors.empty());
    const std::string& B = names.base;
    CHECK(p.one(B + "run/parameters", kGtx + "meshUnit").o == kUnit + "MilliM");
    // Texel 0: contour perimeter 12.5 on the unit-side mesh is 100 mm; area_rel (an area)
    // times 64 mm^2; a dimensionless feature has no quantity.
    const std::string perimeter = B + "texel/0/contour_perimeter";
    CHECK(p.find(B + "texel/0", kGtx + "quantity").size() == 3);
    CHECK(p.one(perimeter, kQudt + "numericValue").o == "1.0E2");
    CHECK(p.one(perimeter, kQudt + "unit").o == kUnit + "MilliM");
    CHECK(p.one(perimeter, kGtx + "ofFeature").o == kGtx + "contour_perimeter");
    const double area_rel = c.seg.features.values(0, 18);
    const std::string area = B + "texel/0/area_rel";
    CHECK(std::stod(p.one(area, kQudt + "numericValue").o) == Approx(area_rel * 64));
    CHECK(p.one(area, kQudt + "unit").o == kUnit + "MilliM2");
    CHECK(p.find(B + "texel/0/contour_sphericity", kQudt + "unit").empty());
    CHECK(p.find(B + "texel/0/shape_index_mean", kQudt + "unit").empty());
    // The texture's measurement has its result in the unit too.
    const std::string m = B + "texture/0/contour_perimeter";
    const std::string q = p.one(m, "http://www.w3.org/ns/sosa/hasResult").o;
    CHECK(q == m + "/quantity");
    CHECK(p.one(q, kQudt + "unit").o == kUnit + "MilliM");
    // Three quantities per texel (perimeter, area_rel, bounding sphere radius), three per texture.
    CHECK(p.subjects_of_type(kQudt + "QuantityValue").size() == 3 * 3 + 3 * 2);

    c.doc.mesh_unit = MeshUnit::Inch;
    const Parsed in = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    CHECK(in.one(run_names(c.doc).base + "texel/0/area_rel", kQudt + "unit").o == kUnit + "IN2");
}

TEST_CASE("parse_mesh_unit: the four units and nothing else", "[ontology][units]") {
    CHECK(parse_mesh_unit("mm") == MeshUnit::Millimetre);
    CHECK(parse_mesh_unit("cm") == MeshUnit::Centimetre);
    CHECK(parse_mesh_unit("m") == MeshUnit::Metre);
    CHECK(parse_mesh_unit("in") == MeshUnit::Inch);
    for (const char* bad : {"", "MM", "mm ", "inch", "km", "µm"}) CHECK_FALSE(parse_mesh_unit(bad));
    for (const MeshUnit u :
         {MeshUnit::Millimetre, MeshUnit::Centimetre, MeshUnit::Metre, MeshUnit::Inch})
        CHECK(parse_mesh_unit(mesh_unit_name(u)) == u);
}

TEST_CASE("write_annotation_rdf: who made the annotations (Web Annotation provenance)",
          "[ontology][rdf]") {
    SmallAnnotationCase c;
    const std::string as = "http://www.w3.org/ns/activitystreams#";
    const std::string software = software_iri(c.doc.software_version);
    CHECK(software == "https://w3id.org/geotex/release/" + c.doc.software_version);
    const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    const std::string a0 = run_names(c.doc).base + "annotation/0";
    CHECK(p.one(a0, as + "generator").o == software);
    CHECK(p.subjects_of_type(as + "Application") == std::set<std::string>{software});
    CHECK(p.find(a0, kDcterms + "creator").empty());
    CHECK(p.find(a0, kDcterms + "created").empty());

    c.doc.creator_iri = "https://museum.example.org/staff/7";
    c.doc.timestamp = "2026-12-01T10:00:00Z";
    const Parsed q = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    const std::string b0 = run_names(c.doc).base + "annotation/0";
    CHECK(q.one(b0, kDcterms + "creator").o == c.doc.creator_iri);
    CHECK(q.one(b0, kDcterms + "created").o == "2026-12-01T10:00:00Z");
    CHECK(q.one(b0, kDcterms + "created").datatype == kXsd + "dateTime");
    CHECK(q.one(run_names(c.doc).base + "texel/0/annotation", as + "generator").o == software);
}
