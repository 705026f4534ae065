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
using test::kMeshDigest;

std::uint64_t bits(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

const char* const kHostile = "a \"quoted\" > file\nwith\r\tstuff \\ \xC3\xA9 \xE6\xBC\xA2.ply";

}  // namespace

TEST_CASE("write_annotation_rdf: Turtle of the small case matches the golden file byte for byte",
          "[ontology][rdf]") {
    SmallCase c;
    const std::string turtle = annotation(c.doc, RdfFormat::Turtle);
    const std::string path = std::string(GEOTEX_SOURCE_DIR) + "/tests/data/golden-small.ttl";
    const std::string golden = read_file(path);
    if (turtle != golden) {
        std::ofstream("golden-small.actual.ttl", std::ios::binary) << turtle;
        FAIL("differs from " << path << "; the output is in golden-small.actual.ttl");
    }
    const Parsed parsed = parse_rdf(turtle, "turtle");
    CHECK(parsed.errors.empty());
    CHECK(parsed.blank_nodes == 0);
}

TEST_CASE("write_annotation_rdf: Turtle, N-Triples and RDF/XML hold the same triples",
          "[ontology][rdf]") {
    SmallCase c;
    const Parsed ttl = parse_rdf(annotation(c.doc, RdfFormat::Turtle), "turtle");
    const Parsed nt = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    const Parsed xml = parse_rdf(annotation(c.doc, RdfFormat::RdfXml), "rdfxml");
    REQUIRE(ttl.errors.empty());
    REQUIRE(nt.errors.empty());
    REQUIRE(xml.errors.empty());
    REQUIRE(!nt.triples.empty());
    CHECK(ttl.triples.size() == nt.triples.size());
    CHECK(xml.triples.size() == nt.triples.size());
    const auto key = [](const ParsedTriple& t) {
        return t.s + "\x1F" + t.p + "\x1F" + t.o + "\x1F" + t.datatype + "\x1F" + t.language;
    };
    std::multiset<std::string> a, b, x;
    for (const auto& t : ttl.triples) a.insert(key(t));
    for (const auto& t : nt.triples) b.insert(key(t));
    for (const auto& t : xml.triples) x.insert(key(t));
    CHECK(a == b);
    CHECK(x == b);
    CHECK(std::set<std::string>(b.begin(), b.end()).size() == b.size());  // no duplicate triple
    CHECK(nt.blank_nodes == 0);
}

TEST_CASE("write_annotation_rdf: doubles read back to the same bits", "[ontology][rdf]") {
    SmallCase c;
    for (const RdfFormat format : {RdfFormat::Turtle, RdfFormat::NTriples, RdfFormat::RdfXml}) {
        const char* syntax = format == RdfFormat::Turtle     ? "turtle"
                             : format == RdfFormat::NTriples ? "ntriples"
                                                             : "rdfxml";
        const Parsed p = parse_rdf(annotation(c.doc, format), syntax);
        REQUIRE(p.errors.empty());
        const std::vector<std::string> shortcuts = {"contourPerimeter",
                                                    "contourSphericity",
                                                    "localDiameterMean",
                                                    "localDiameterStd",
                                                    "area",
                                                    "boundingSphereRadius",
                                                    "perimeter2AreaRatio",
                                                    "pcaVariance1"};
        const RunNames names = run_names(c.doc);
        for (int i = 0; i < 3; ++i)
            for (std::size_t j = 0; j < shortcuts.size(); ++j) {
                const auto& t =
                    p.one(names.base + "texel/" + std::to_string(i), kGtx + shortcuts[j]);
                CHECK(t.datatype == kXsd + "double");
                CHECK(t.o.find('E') != std::string::npos);
                const double v = c.seg.features.values(i, static_cast<Eigen::Index>(j));
                CHECK(bits(std::strtod(t.o.c_str(), nullptr)) == bits(v));
            }
        // -0.0 keeps its sign; the mean of texture 0's first feature is exact.
        CHECK(p.one(names.base + "texel/0", kGtx + "localDiameterStd").o == "-0.0E0");
        CHECK(p.one(names.base + "texel/0", kGtx + "contourPerimeter").o == "1.25E1");
        CHECK(p.one(names.base + "texel/0", kGtx + "area").o == "1.0E-1");
        const auto& unit = p.one(names.mesh, kGtx + "unitScale");
        CHECK(unit.o == "1.25E-1");
        CHECK(unit.datatype == kXsd + "double");
    }
}

TEST_CASE("write_annotation_rdf: the model of ontology/README.md", "[ontology][rdf]") {
    SmallCase c;
    const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    REQUIRE(p.errors.empty());
    const RunNames names = run_names(c.doc);
    const std::string& B = names.base;
    CHECK(B.rfind(c.doc.base_iri + "run/", 0) == 0);
    CHECK(names.mesh == c.doc.base_iri + "mesh");
    CHECK(p.subjects_of_type(kGtx + "Texel").size() == 3);
    CHECK(p.subjects_of_type(kGtx + "FaceSetSelector").size() == 3);
    CHECK(p.subjects_of_type(kGtx + "GeometricTexture").size() == 2);
    CHECK(p.subjects_of_type(kGtx + "FeatureMeasurement").size() == 2 * kNumFeatures);
    CHECK(p.one(names.mesh, kGtx + "faceCount").o == "16");
    CHECK(p.one(names.mesh, kGtx + "vertexCount").o == "18");
    CHECK(p.one(B + "run", kGtx + "runKey").o == names.key);

    // The run used the mesh, the parameters, the scheme and the version of the dictionary
    // (the scheme's IRI is the same for every version), which the graph describes even
    // without the dictionary.
    const std::string prov = "http://www.w3.org/ns/prov#";
    CHECK(p.find(B + "run", prov + "used").size() == 4);
    const std::string scheme = c.dictionary.namespace_iri + "scheme";
    const std::string used = scheme + "/version/1.0";
    CHECK(p.subjects_of_type(kGtx + "DictionaryVersion") == std::set<std::string>{used});
    CHECK(p.subjects_of_type(prov + "Entity").count(used) == 1);
    std::set<std::string> used_nodes;
    for (const auto* t : p.find(B + "run", prov + "used")) used_nodes.insert(t->o);
    CHECK(used_nodes.count(used) == 1);
    CHECK(used_nodes.count(scheme) == 1);
    CHECK(p.one(used, prov + "specializationOf").o == scheme);
    CHECK(p.one(used, "http://purl.org/dc/terms/isVersionOf").o == scheme);
    CHECK(p.one(used, "http://www.w3.org/2002/07/owl#versionInfo").o == "1.0");
    CHECK(p.one(used, kGtx + "sha256").o == c.dictionary.sha256);
    CHECK(p.find(B + "run/dictionary", kRdfType).empty());
    // A measurement with a concept names the interval of that version that held its value.
    CHECK(p.one(B + "texture/0/contour_sphericity", kGtx + "interval").o ==
          used + "/circular-shape");
    CHECK(p.find(B + "texture/0/depth_mean", kGtx + "interval").empty());

    // Texel 0: faces 0..2 of the strip, area 1.5, centroid (8/9, 4/9, 0) / 8 on the unit-side
    // mesh. Tolerance: a few ulps of the summation over three faces.
    CHECK(p.one(B + "texel/0/faces", "http://www.w3.org/1999/02/22-rdf-syntax-ns#value").o ==
          "0-2");
    std::istringstream centroid(p.one(B + "texel/0", kGtx + "centroid").o);
    double x = 0, y = 0, z = 0;
    centroid >> x >> y >> z;
    CHECK(x == Approx(8.0 / 9.0 / 8.0).epsilon(1e-14));
    CHECK(y == Approx(4.0 / 9.0 / 8.0).epsilon(1e-14));
    CHECK(z == 0);

    // Over the cap: count and digest of the ranges text, no ranges.
    CHECK(p.find(B + "texel/1/faces", "http://www.w3.org/1999/02/22-rdf-syntax-ns#value").empty());
    CHECK(p.one(B + "texel/1/faces", kGtx + "facesSha256").o == sha256_hex("5-7 9"));
    CHECK(p.one(B + "texel/1/faces", kGtx + "faceCount").o == "4");
    CHECK(p.one(B + "texel/1", kGtx + "orientation").o == kGtx + "NegativeDetails");

    // Annotation 0: bodies are the chosen concepts, its one target the texture as a whole,
    // a part of the mesh made of its two texels.
    const std::string oa = "http://www.w3.org/ns/oa#";
    const auto objects = [&](const std::string& s, const std::string& pred) {
        std::set<std::string> out;
        for (const auto* t : p.find(s, pred)) out.insert(t->o);
        return out;
    };
    CHECK(objects(B + "annotation/0", oa + "hasBody") ==
          std::set<std::string>{"https://example.org/dict/circular-shape",
                                "https://example.org/dict/small-area"});
    CHECK(objects(B + "annotation/0", oa + "hasTarget") == std::set<std::string>{B + "texture/0"});
    CHECK(objects(B + "annotation/0", kGtx + "describes") ==
          std::set<std::string>{B + "texture/0"});
    CHECK(objects(B + "annotation/0", kGtx + "justifiedBy") ==
          std::set<std::string>{B + "texture/0/contour_sphericity", B + "texture/0/area"});
    CHECK(p.subjects_of_type(oa + "SpecificResource").count(B + "texture/0") == 1);
    CHECK(p.one(B + "texture/0", oa + "hasSource").o == names.mesh);
    CHECK(objects(B + "texture/0", kGtx + "hasTexel") ==
          std::set<std::string>{B + "texel/0", B + "texel/2"});
    CHECK(objects(B + "texture/1", kGtx + "hasTexel") == std::set<std::string>{B + "texel/1"});
    // Its score is its weakest body's: stability 0.9 and agreement 0.5 (small area).
    CHECK(p.one(B + "annotation/0", kGtx + "stability").o == "9.0E-1");
    CHECK(p.one(B + "annotation/0", kGtx + "agreement").o == "5.0E-1");
    CHECK(p.one(B + "annotation/1", kGtx + "stability").o == "1.0E0");

    // The texel annotations: what holds for each texel's own values. Texel 2's area (0.3) is
    // large although its texture's mean (0.2) is small.
    CHECK(objects(B + "texel/0/annotation", oa + "hasBody") ==
          std::set<std::string>{"https://example.org/dict/circular-shape",
                                "https://example.org/dict/small-area"});
    CHECK(objects(B + "texel/2/annotation", oa + "hasBody") ==
          std::set<std::string>{"https://example.org/dict/circular-shape",
                                "https://example.org/dict/large-area"});
    CHECK(objects(B + "texel/1/annotation", oa + "hasBody") ==
          std::set<std::string>{"https://example.org/dict/elongated"});
    for (const char* i : {"0", "1", "2"}) {
        const std::string a = B + "texel/" + i + "/annotation";
        CHECK(objects(a, oa + "hasTarget") == std::set<std::string>{B + "texel/" + i});
        CHECK(p.subjects_of_type(kGtx + "TexelAnnotation").count(a) == 1);
        CHECK(p.find(a, kGtx + "describes").empty());
    }
    CHECK(p.subjects_of_type(oa + "Annotation").size() == 2 + 3);

    // Measurements: significance and rank absent when S is undefined; the concept when one
    // holds the value, chosen or not.
    const std::string m5 = B + "texture/0/bounding_sphere_radius";
    CHECK(p.find(m5, kGtx + "significance").empty());
    CHECK(p.find(m5, kGtx + "rank").empty());
    CHECK(p.one(m5, kGtx + "chosen").o == "false");
    CHECK(p.find(m5, kGtx + "agreement").empty());  // no concept
    CHECK(p.find(m5, kGtx + "stability").empty());  // not picked by the rule
    CHECK(p.find(m5, kGtx + "withheld").empty());
    const std::string m9 = B + "texture/0/pca_variance_3";  // picked, but not stable enough
    CHECK(p.one(m9, kGtx + "concept").o == "https://example.org/dict/flat");
    CHECK(p.one(m9, kGtx + "chosen").o == "false");
    CHECK(p.one(m9, kGtx + "withheld").o == "true");
    CHECK(p.one(m9, kGtx + "stability").o == "6.25E-1");
    CHECK(p.one(m9, kGtx + "agreement").o == "5.0E-1");
    const std::string m1 = B + "texture/0/contour_sphericity";
    CHECK(p.one(m1, kGtx + "rank").o == "2");
    CHECK(p.one(m1, kGtx + "stability").o == "9.85E-1");
    CHECK(p.one(m1, kGtx + "agreement").o == "1.0E0");
    CHECK(p.one(m1, kGtx + "stability").datatype == kXsd + "double");
    CHECK(p.find(m1, kGtx + "withheld").empty());

    // Texture labels in the requested language, joined in rank order.
    const auto& label = p.one(B + "texture/0", "http://www.w3.org/2000/01/rdf-schema#label");
    CHECK(label.o == "circular shape, small area");
    CHECK(label.language == "en");
    c.doc.label_language = "fr";
    const Parsed fr = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    // (the label's language is in the run key: the texture of this run has another IRI)
    CHECK(fr.one(run_names(c.doc).base + "texture/1", "http://www.w3.org/2000/01/rdf-schema#label")
              .o == "allongé");
    c.doc.label_language = "de";  // not in the dictionary: falls back to its first language
    const Parsed de = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    CHECK(de.one(run_names(c.doc).base + "texture/1", "http://www.w3.org/2000/01/rdf-schema#label")
              .language == "en");
    c.doc.label_language = "en";

    // The run: no time unless given; then an xsd:dateTime.
    CHECK(p.find(B + "run", "http://www.w3.org/ns/prov#endedAtTime").empty());
    c.doc.timestamp = "2026-11-25T18:00:00Z";
    const Parsed stamped = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    // A run at another time is another activity: new run IRIs, the same mesh.
    const RunNames stamped_names = run_names(c.doc);
    CHECK(stamped_names.base != B);
    CHECK(stamped_names.mesh == names.mesh);
    const auto& ended =
        stamped.one(stamped_names.base + "run", "http://www.w3.org/ns/prov#endedAtTime");
    CHECK(ended.o == "2026-11-25T18:00:00Z");
    CHECK(ended.datatype == kXsd + "dateTime");
    // The time of the run, and of each annotation (dcterms:created).
    const std::size_t annotations =
        stamped.subjects_of_type("http://www.w3.org/ns/oa#Annotation").size();
    CHECK(stamped.triples.size() == p.triples.size() + 1 + annotations);
    c.doc.timestamp.clear();

    // Parameters: scale only without an absolute radius; the cap on concepts only when set.
    const std::string params = B + "run/parameters";
    CHECK(p.one(params, kGtx + "scale").o == "4.0E-2");
    CHECK(p.one(params, kGtx + "maxConcepts").o == "2");
    CHECK(p.one(params, kGtx + "maxSignificance").o == "5.0E-1");
    CHECK(p.one(params, kGtx + "minAgreement").o == "7.5E-1");
    CHECK(p.one(params, kGtx + "minStability").o == "9.0E-1");
    CHECK(p.one(params, kGtx + "resamples").o == "200");
    CHECK(p.find(params, kGtx + "conceptsPerTexture").empty());
    c.doc.description.max_concepts = 0;
    // (each option is in the run key: the parameter set of this run has another IRI)
    const std::string uncapped = run_names(c.doc).base + "run/parameters";
    CHECK(uncapped != params);
    const Parsed no_cap = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    CHECK(no_cap.one(uncapped, kGtx + "resamples").o == "200");
    CHECK(no_cap.find(uncapped, kGtx + "maxConcepts").empty());
    c.doc.params.radius = 2;
    const Parsed absolute = parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples");
    CHECK(absolute.find(run_names(c.doc).base + "run/parameters", kGtx + "scale").empty());
}

TEST_CASE("write_annotation_rdf: hostile strings round-trip exactly and inject nothing",
          "[ontology][rdf]") {
    SmallCase c;
    const std::size_t plain_count =
        parse_rdf(annotation(c.doc, RdfFormat::NTriples), "ntriples").triples.size();
    const std::string hostile = kHostile;
    c.doc.mesh_file = hostile;
    c.doc.mesh_format = hostile + " .\n<a> <b> <c> .";
    c.doc.software_version = "1\r\" ; <x> \"y";  // a carriage return without a line feed
    c.dictionary.concepts[0].labels["en"] = hostile;
    c.dictionary.concepts[1].labels["en"] = "\"\"\"triple\"\"\" '''quotes''' \\";
    c.dictionary.concepts[0].id = "a b/c?d#e>f\"%20é";
    c.dictionary.namespace_iri = "https://example.org/d%C3%A9mo/dict#";
    c.doc.base_iri = "https://example.org/objets/vase-été/";
    const std::string concept_iri =
        "https://example.org/d%C3%A9mo/dict#a%20b%2Fc%3Fd%23e%3Ef%22%2520%C3%A9";

    for (const RdfFormat format : {RdfFormat::Turtle, RdfFormat::NTriples, RdfFormat::RdfXml}) {
        const char* syntax = format == RdfFormat::Turtle     ? "turtle"
                             : format == RdfFormat::NTriples ? "ntriples"
                                                             : "rdfxml";
        INFO(syntax);
        const std::string text = annotation(c.doc, format);
        if (format == RdfFormat::Turtle) CHECK(text.find('\r') == std::string::npos);
        const Parsed p = parse_rdf(text, syntax);
        REQUIRE(p.errors.empty());
        CHECK(p.triples.size() == plain_count);
        const RunNames names = run_names(c.doc);
        const std::string& B = names.base;
        CHECK(p.one(names.mesh, "http://purl.org/dc/terms/identifier").o == hostile);
        CHECK(p.one(names.mesh, kGtx + "fileFormat").o == c.doc.mesh_format);
        CHECK(
            p.one(software_iri(c.doc.software_version), "http://www.w3.org/2002/07/owl#versionInfo")
                .o == c.doc.software_version);
        CHECK(p.one(B + "texture/0", "http://www.w3.org/2000/01/rdf-schema#label").o ==
              hostile + ", \"\"\"triple\"\"\" '''quotes''' \\");
        CHECK(p.one(B + "texture/0/contour_sphericity", kGtx + "concept").o == concept_iri);
    }

    // The dictionary with the same strings.
    c.dictionary.titles["fr"] = hostile;
    c.dictionary.concepts[2].definitions["fr"] = hostile;
    c.dictionary.concepts[2].source = hostile;
    c.dictionary.version = "2.0 \xCE\xB2/rc?#..";  // "2.0 β/rc?#..": one segment of the IRIs
    for (const RdfFormat format : {RdfFormat::Turtle, RdfFormat::NTriples, RdfFormat::RdfXml}) {
        const char* syntax = format == RdfFormat::Turtle     ? "turtle"
                             : format == RdfFormat::NTriples ? "ntriples"
                                                             : "rdfxml";
        INFO(syntax);
        const Parsed p = parse_rdf(dictionary_rdf(c.dictionary, format), syntax);
        REQUIRE(p.errors.empty());
        CHECK(p.one(concept_iri, "http://www.w3.org/2004/02/skos/core#notation").o ==
              c.dictionary.concepts[0].id);
        std::map<std::string, std::string> labels;
        for (const auto* t : p.find(concept_iri, "http://www.w3.org/2004/02/skos/core#prefLabel"))
            labels[t->language] = t->o;
        CHECK(labels == c.dictionary.concepts[0].labels);
        const std::string version =
            "https://example.org/d%C3%A9mo/dict#scheme/version/2.0%20%CE%B2%2Frc%3F%23..";
        CHECK(p.one(version, "http://www.w3.org/2002/07/owl#versionInfo").o ==
              c.dictionary.version);
        const std::string elongated = version + "/elongated";
        CHECK(p.one(elongated, "http://www.w3.org/2004/02/skos/core#definition").o == hostile);
        CHECK(p.one(elongated, "http://purl.org/dc/terms/source").o == hostile);
        // 5 concepts and 4 facets
        CHECK(p.subjects_of_type("http://www.w3.org/2004/02/skos/core#Concept").size() == 9);
    }
}

TEST_CASE("write_annotation_rdf: strings that no syntax can carry are InvalidInput",
          "[ontology][rdf]") {
    SmallCase c;
    std::ostringstream out;
    SECTION("control character") { c.doc.mesh_file = std::string("a\x01.ply"); }
    SECTION("NUL") { c.doc.mesh_file = std::string("a\0b.ply", 7); }
    SECTION("DEL") { c.doc.mesh_file = "a\x7F.ply"; }
    SECTION("invalid UTF-8") { c.doc.mesh_file = "caf\xE9.ply"; }
    SECTION("surrogate in UTF-8") { c.dictionary.concepts[0].labels["en"] = "\xED\xA0\x80"; }
    SECTION("non-character") { c.dictionary.concepts[0].labels["en"] = "\xEF\xBF\xBE"; }
    SECTION("bad language tag") { c.doc.label_language = "en fr"; }
    REQUIRE_THROWS_AS(write_annotation_rdf(out, c.doc, RdfFormat::Turtle), InvalidInput);
    CHECK(out.str().empty());  // nothing is written before every check has passed
}

// The preconditions of write_annotation_rdf (tests/annotation_case.cpp, broken_cases) are
// checked together with those of write_annotation_jsonld in test_jsonld_writer.cpp.

TEST_CASE("write_annotation_rdf: a run without texels describes the mesh and the run",
          "[ontology][rdf]") {
    SmallCase c;
    c.seg.texels.clear();
    c.seg.face_texel.assign(16, -1);
    c.seg.texel_texture.clear();
    c.seg.features.values.resize(0, kNumFeatures);
    c.seg.num_textures = 0;
    c.seg.texture_orientation.clear();
    c.descriptions.clear();
    const Parsed p = parse_rdf(annotation(c.doc, RdfFormat::Turtle), "turtle");
    REQUIRE(p.errors.empty());
    CHECK(p.subjects_of_type(kGtx + "Texel").empty());
    CHECK(p.subjects_of_type(kGtx + "GeometricTexture").empty());
    CHECK(p.subjects_of_type(kGtx + "Mesh").size() == 1);
    CHECK(p.subjects_of_type(kGtx + "TextureAnalysis").size() == 1);
}

TEST_CASE("write_annotation_rdf: a failing stream is an IoError", "[ontology][rdf]") {
    SmallCase c;
    std::ofstream closed;  // never opened: every write fails
    REQUIRE_THROWS_AS(write_annotation_rdf(closed, c.doc, RdfFormat::NTriples), IoError);
    REQUIRE_THROWS_AS(write_dictionary_rdf(closed, c.dictionary, RdfFormat::Turtle), IoError);
    // A stream that throws on failure: the exception must not cross Raptor's C code.
    struct FailingBuffer : std::streambuf {
        int overflow(int) override { return traits_type::eof(); }
        std::streamsize xsputn(const char*, std::streamsize) override { return 0; }
    } buffer;
    std::ostream throwing(&buffer);
    throwing.exceptions(std::ios::badbit);
    REQUIRE_THROWS_AS(write_annotation_rdf(throwing, c.doc, RdfFormat::Turtle), IoError);
}

TEST_CASE("write_annotation_rdf: deterministic", "[ontology][rdf]") {
    for (const RdfFormat format : {RdfFormat::Turtle, RdfFormat::NTriples, RdfFormat::RdfXml}) {
        SmallCase a;
        const std::string first = annotation(a.doc, format);
        CHECK(annotation(a.doc, format) == first);
        SmallCase b;  // another document with equal content, at other addresses
        CHECK(annotation(b.doc, format) == first);
        CHECK(dictionary_rdf(a.dictionary, format) == dictionary_rdf(b.dictionary, format));
    }
}

TEST_CASE("face_ranges: sorted faces as inclusive ranges", "[ontology][rdf]") {
    CHECK(face_ranges({}).empty());
    CHECK(face_ranges({0}) == "0");
    CHECK(face_ranges({4, 5}) == "4-5");
    CHECK(face_ranges({1, 2, 3}) == "1-3");
    CHECK(face_ranges({0, 1, 3, 5, 6, 7, 10}) == "0-1 3 5-7 10");
    CHECK(face_ranges({812, 813, 840, 902}) == "812-813 840 902");
    CHECK(face_ranges({2147483646, 2147483647}) == "2147483646-2147483647");
    REQUIRE_THROWS_AS(face_ranges({3, 3}), InvalidInput);
    REQUIRE_THROWS_AS(face_ranges({2, 1}), InvalidInput);
    REQUIRE_THROWS_AS(face_ranges({-1, 0}), InvalidInput);
}

TEST_CASE("validate_base_iri: absolute IRIs ending in / or #", "[ontology][rdf]") {
    for (const char* ok : {"https://example.org/a/", "urn:sha256:abc/", "http://x/#", "urn:x#",
                           "https://example.org/%C3%A9/", "https://example.org/été/",
                           "http://x/?a=1&b='2'/", "tag:museum.example,2026:vase-42/"})
        CHECK(validate_base_iri(ok) == ok);
    for (const char* bad : {"", "example.org/", "https://x/a", "https://x/a b/", "https://x/<a>/",
                            "https://x/\"/", "https://x/{a}/", "https://x/a|b/", "https://x/a\\b/",
                            "https://x/a^b/", "https://x/`/", "https://x/\n/", "https://x/%zz/",
                            "https://x/#a#", "1http://x/", "http:", "caf\xE9:x/"}) {
        INFO(bad);
        CHECK_THROWS_AS(validate_base_iri(bad), InvalidInput);
    }
    // The message names the character and its position (in characters, 1-based).
    CHECK_THROWS_WITH(validate_base_iri("https://é.org/a>b/"),
                      Catch::Contains("'>'") && Catch::Contains("position 16"));
    CHECK_THROWS_WITH(validate_base_iri("https://x/a b/"),
                      Catch::Contains("space") && Catch::Contains("position 12"));
}
