#include <catch2/catch.hpp>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "ontology/jsonld_writer.hpp"
#include "ontology/rdf_writer.hpp"
#include "tests/annotation_case.hpp"

using namespace geotex;
using test::SmallAnnotationCase;
using Json = nlohmann::json;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::string kGtx = kGeotexNs;
const std::string kOa = "http://www.w3.org/ns/oa#";

std::string jsonld(const AnnotationDocument& doc) {
    std::ostringstream out;
    write_annotation_jsonld(out, doc);
    return out.str();
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The triples of N-Triples text whose object is an IRI, as (subject, predicate, object). The
/// small case's IRIs are ASCII, which Raptor writes as they are.
std::set<std::vector<std::string>> iri_triples(const std::string& ntriples) {
    std::set<std::vector<std::string>> out;
    std::istringstream in(ntriples);
    std::string line;
    while (std::getline(in, line)) {
        // "<s> <p> <o> ." and nothing else; an IRI holds no '>'.
        std::vector<std::string> iris;
        std::size_t at = 0;
        while (iris.size() < 3 && at < line.size() && line[at] == '<') {
            const std::size_t close = line.find('>', at);
            if (close == std::string::npos) break;
            iris.push_back(line.substr(at + 1, close - at - 1));
            at = close + 1;
            if (iris.size() == 3) break;
            if (line.compare(at, 2, " <") != 0) break;
            ++at;
        }
        if (iris.size() == 3 && line.compare(at, std::string::npos, " .") == 0) out.insert(iris);
    }
    return out;
}

/// Objects of (subject, predicate) among the triples.
std::set<std::string> objects(const std::set<std::vector<std::string>>& triples,
                              const std::string& s, const std::string& p) {
    std::set<std::string> out;
    for (const auto& t : triples)
        if (t[0] == s && t[1] == p) out.insert(t[2]);
    return out;
}

/// "id" of a JSON-LD node, or the node itself when it is an IRI string.
std::string id_of(const Json& node) {
    return node.is_string() ? node.get<std::string>() : node.at("id").get<std::string>();
}

}  // namespace

TEST_CASE("write_annotation_jsonld: the small case matches the golden file byte for byte",
          "[ontology][jsonld]") {
    SmallAnnotationCase c;
    c.doc.include_dictionary = true;
    const std::string text = jsonld(c.doc);
    const std::string path = std::string(GEOTEX_SOURCE_DIR) + "/tests/data/golden-small.jsonld";
    if (text != read_file(path)) {
        std::ofstream("golden-small.actual.jsonld", std::ios::binary) << text;
        FAIL("differs from " << path << "; the output is in golden-small.actual.jsonld");
    }
    CHECK(Json::accept(text));
}

TEST_CASE("write_annotation_jsonld: an AnnotationPage with one Annotation per texture and texel",
          "[ontology][jsonld]") {
    SmallAnnotationCase c;
    c.doc.include_dictionary = true;
    const Json page = Json::parse(jsonld(c.doc));
    const RunNames names = run_names(c.doc);
    const std::string B = names.base;
    const std::string ns = c.dictionary.namespace_iri;
    REQUIRE(page.at("@context").size() == 2);
    CHECK(page["@context"][0] == "http://www.w3.org/ns/anno.jsonld");
    CHECK(page["@context"][1]["gtx"] == kGtx);
    CHECK(page["id"] == B + "annotations");
    CHECK(page["type"] == "AnnotationPage");
    const Json& items = page.at("items");
    REQUIRE(items.size() == 2 + 3);

    const Json& a0 = items[0];
    CHECK(a0["id"] == B + "annotation/0");
    CHECK(a0["type"] == "Annotation");
    CHECK(a0["motivation"] == "classifying");
    // Bodies: the chosen concepts, most significant first, with their labels.
    REQUIRE(a0.at("body").size() == 2);
    CHECK(a0["body"][0]["id"] == ns + "circular-shape");
    CHECK(a0["body"][0]["type"] == "skos:Concept");
    CHECK(a0["body"][0]["prefLabel"] == Json{{"en", "circular shape"}, {"fr", "forme circulaire"}});
    CHECK(a0["body"][1]["id"] == ns + "small-area");
    CHECK(a0["justifiedBy"] ==
          Json::array({B + "texture/0/contour_sphericity", B + "texture/0/area"}));
    CHECK(a0["describes"] == B + "texture/0");
    // The weakest body's scores, as xsd:double lexical forms.
    CHECK(a0["stability"] == "9.0E-1");
    CHECK(a0["agreement"] == "5.0E-1");
    CHECK(page["@context"][1]["stability"] ==
          Json{{"@id", "gtx:stability"}, {"@type", "http://www.w3.org/2001/XMLSchema#double"}});
    // The target: the texture as a whole, a part of the mesh made of texels 0 and 2, each
    // with its face selector.
    const Json& texture0 = a0.at("target");
    CHECK(texture0["id"] == B + "texture/0");
    CHECK(texture0["type"] == Json::array({"SpecificResource", "gtx:GeometricTexture"}));
    CHECK(texture0["source"] == names.mesh);
    REQUIRE(texture0.at("hasTexel").size() == 2);
    const Json& texel0 = texture0["hasTexel"][0];
    CHECK(texel0["id"] == B + "texel/0");
    CHECK(texel0["type"] == Json::array({"SpecificResource", "gtx:Texel"}));
    CHECK(texel0["source"] == names.mesh);
    CHECK(texel0["selector"]["id"] == B + "texel/0/faces");
    CHECK(texel0["selector"]["type"] == "gtx:FaceSetSelector");
    CHECK(texel0["selector"]["conformsTo"] == "gtx:FaceSetSelectorSpec");
    CHECK(texel0["selector"]["faceRanges"] == "0-2");
    CHECK(texel0["selector"]["faceCount"] == 3);
    CHECK(texel0["selector"]["boundToMesh"] == test::kMeshDigest);
    // Texel 2 has 4 faces, above the case's cap of 3: a digest instead of the ranges.
    const Json& texel2 = texture0["hasTexel"][1];
    CHECK(texel2["id"] == B + "texel/2");
    CHECK_FALSE(texel2["selector"].contains("faceRanges"));
    CHECK(texel2["selector"]["facesSha256"].get<std::string>().size() == 64);
    CHECK(texel2["selector"]["faceCount"] == 4);

    const Json& a1 = items[1];
    CHECK(a1["id"] == B + "annotation/1");
    REQUIRE(a1.at("body").size() == 1);
    CHECK(a1["body"][0]["prefLabel"]["fr"] == "allongé");
    REQUIRE(a1.at("target").at("hasTexel").size() == 1);
    CHECK(a1["target"]["id"] == B + "texture/1");
    CHECK(a1["target"]["hasTexel"][0]["id"] == B + "texel/1");

    // Then the texels, each with what holds for its own values; texel 2's own area is large.
    for (std::size_t i = 0; i < 3; ++i) {
        const Json& a = items[2 + i];
        INFO("texel " << i);
        CHECK(a["id"] == B + "texel/" + std::to_string(i) + "/annotation");
        CHECK(a["type"] == Json::array({"Annotation", "gtx:TexelAnnotation"}));
        CHECK(a["motivation"] == "classifying");
        CHECK(a["target"]["id"] == B + "texel/" + std::to_string(i));
        CHECK(a["target"]["selector"]["id"] == B + "texel/" + std::to_string(i) + "/faces");
        CHECK_FALSE(a.contains("describes"));
    }
    CHECK(items[4]["body"].size() == 2);
    CHECK(items[4]["body"][0]["id"] == ns + "circular-shape");
    CHECK(items[4]["body"][1]["id"] == ns + "large-area");
    CHECK(items[4]["body"][1]["prefLabel"]["fr"] == "grande aire");

    // Without the dictionary in the graph, bodies are the concept IRIs alone, so that every
    // triple stays one of the Turtle's.
    c.doc.include_dictionary = false;
    const Json bare = Json::parse(jsonld(c.doc));
    CHECK(bare["items"][0]["body"] == Json::array({ns + "circular-shape", ns + "small-area"}));
}

TEST_CASE("write_annotation_jsonld: the IRIs, bodies and targets of the Turtle",
          "[ontology][jsonld]") {
    SmallAnnotationCase c;
    for (const bool with_dictionary : {false, true}) {
        INFO("include_dictionary " << with_dictionary);
        c.doc.include_dictionary = with_dictionary;
        const auto triples = iri_triples([&] {
            std::ostringstream out;
            write_annotation_rdf(out, c.doc, RdfFormat::NTriples);
            return out.str();
        }());
        REQUIRE(!triples.empty());
        std::set<std::string> subjects;
        for (const auto& t : triples) subjects.insert(t[0]);
        const Json page = Json::parse(jsonld(c.doc));
        const std::string rdf_type = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type";
        std::set<std::string> annotations;
        for (const Json& a : page["items"]) {
            const std::string id = a["id"];
            annotations.insert(id);
            std::set<std::string> bodies;
            for (const Json& b : a.value("body", Json::array())) bodies.insert(id_of(b));
            // One target: a texture (with its texels) or a texel (with its selector).
            const Json& target = a["target"];
            REQUIRE(target.is_object());
            CHECK(objects(triples, target["id"], kOa + "hasSource") ==
                  std::set<std::string>{target["source"].get<std::string>()});
            const auto check_texel = [&](const Json& t) {
                CHECK(objects(triples, t["id"], kOa + "hasSource") ==
                      std::set<std::string>{t["source"].get<std::string>()});
                CHECK(objects(triples, t["id"], kOa + "hasSelector") ==
                      std::set<std::string>{t["selector"]["id"].get<std::string>()});
                CHECK(subjects.count(t["selector"]["id"]) == 1);
            };
            if (target.contains("hasTexel")) {
                std::set<std::string> texels;
                for (const Json& t : target["hasTexel"]) {
                    texels.insert(t["id"].get<std::string>());
                    check_texel(t);
                }
                CHECK(texels == objects(triples, target["id"], kGtx + "hasTexel"));
                CHECK(objects(triples, id, kGtx + "describes") ==
                      std::set<std::string>{a["describes"].get<std::string>()});
            } else {
                check_texel(target);
                CHECK_FALSE(a.contains("describes"));
                CHECK(objects(triples, id, kGtx + "describes").empty());
            }
            CHECK(bodies == objects(triples, id, kOa + "hasBody"));
            CHECK(objects(triples, id, kOa + "hasTarget") ==
                  std::set<std::string>{target["id"].get<std::string>()});
            std::set<std::string> justified;
            for (const Json& m : a.value("justifiedBy", Json::array()))
                justified.insert(m.get<std::string>());
            CHECK(justified == objects(triples, id, kGtx + "justifiedBy"));
            if (with_dictionary)
                for (const std::string& b : bodies) CHECK(subjects.count(b) == 1);
        }
        std::set<std::string> rdf_annotations;
        for (const auto& t : triples)
            if (t[1] == rdf_type && t[2] == kOa + "Annotation") rdf_annotations.insert(t[0]);
        CHECK(annotations == rdf_annotations);
    }
}

TEST_CASE("write_annotation_jsonld: hostile strings round-trip exactly", "[ontology][jsonld]") {
    SmallAnnotationCase c;
    c.doc.include_dictionary = true;
    const std::string hostile =
        "a \"quoted\" \\ label\nwith\r\tcontrols </script> \xE2\x80\xA8 \xC3\xA9 \xE6\xBC\xA2 "
        "\"}, \"@id\": \"x";
    c.dictionary.concepts[0].labels["en"] = hostile;
    c.dictionary.concepts[0].labels["pt-BR"] = "@value";
    c.dictionary.concepts[0].id = "a b/c?d#e>f\"%20é";
    c.dictionary.namespace_iri = "https://example.org/d%C3%A9mo/dict#";
    c.doc.base_iri = "https://example.org/objets/vase-été/";
    c.doc.mesh_file = hostile;  // in the Turtle only; must not break the JSON-LD either
    const std::string text = jsonld(c.doc);
    // No raw control character: the only ones are the line feeds of the indentation.
    for (const char ch : text) CHECK((static_cast<unsigned char>(ch) >= 0x20 || ch == '\n'));
    const Json page = Json::parse(text);
    const Json& body = page["items"][0]["body"][0];
    CHECK(body["id"] == "https://example.org/d%C3%A9mo/dict#a%20b%2Fc%3Fd%23e%3Ef%22%2520%C3%A9");
    CHECK(body["prefLabel"]["en"] == hostile);
    CHECK(body["prefLabel"]["pt-BR"] == "@value");
    CHECK(body["prefLabel"]["fr"] == "forme circulaire");
    CHECK(page["id"] == run_names(c.doc).base + "annotations");
    CHECK(page["id"].get<std::string>().rfind("https://example.org/objets/vase-été/run/", 0) == 0);
    CHECK(page["items"][0]["target"]["source"] == "https://example.org/objets/vase-été/mesh");
    CHECK(page["items"][0]["target"]["hasTexel"][0]["source"] ==
          "https://example.org/objets/vase-été/mesh");
    // Nothing added: the same keys and counts as with plain strings.
    SmallAnnotationCase plain;
    plain.doc.include_dictionary = true;
    const Json reference = Json::parse(jsonld(plain.doc));
    CHECK(page["items"].size() == reference["items"].size());
    CHECK(page["items"][0].size() == reference["items"][0].size());
    CHECK(body.size() == reference["items"][0]["body"][0].size());
}

TEST_CASE("write_annotation_rdf and write_annotation_jsonld: the same preconditions",
          "[ontology][rdf][jsonld]") {
    for (const test::BrokenCase& broken : test::broken_cases()) {
        DYNAMIC_SECTION(broken.name) {
            SmallAnnotationCase c;
            c.doc.include_dictionary = true;
            broken.apply(c);
            // Nothing is written before every check has passed.
            std::ostringstream rdf, jsonld;
            REQUIRE_THROWS_AS(write_annotation_rdf(rdf, c.doc, RdfFormat::NTriples), InvalidInput);
            CHECK(rdf.str().empty());
            REQUIRE_THROWS_AS(write_annotation_jsonld(jsonld, c.doc), InvalidInput);
            CHECK(jsonld.str().empty());
        }
    }
}

TEST_CASE("write_annotation_jsonld: messages name the JSON-LD writer", "[ontology][jsonld]") {
    SmallAnnotationCase c;
    c.doc.mesh_file.clear();
    std::ostringstream out;
    REQUIRE_THROWS_WITH(write_annotation_jsonld(out, c.doc),
                        Catch::StartsWith("write_annotation_jsonld: "));
    REQUIRE_THROWS_WITH(write_annotation_rdf(out, c.doc, RdfFormat::Turtle),
                        Catch::StartsWith("write_annotation_rdf: "));
}

TEST_CASE("write_annotation_jsonld: an IRI that JSON-LD would read as a compact IRI is refused",
          "[ontology][jsonld]") {
    SmallAnnotationCase c;
    std::ostringstream out;
    SECTION("base with the scheme of a W3C prefix") {
        c.doc.base_iri = "oa:objects/vase/";
        // Valid for the Turtle, where it is an absolute IRI like any other.
        std::ostringstream turtle;
        CHECK_NOTHROW(write_annotation_rdf(turtle, c.doc, RdfFormat::Turtle));
    }
    SECTION("base with the scheme of a W3C term") { c.doc.base_iri = "target:vase/"; }
    SECTION("base with the scheme of a geotex term") { c.doc.base_iri = "gtx:vase/"; }
    SECTION("dictionary namespace") { c.dictionary.namespace_iri = "skos:mine/"; }
    REQUIRE_THROWS_AS(write_annotation_jsonld(out, c.doc), InvalidInput);
    CHECK(out.str().empty());
}

TEST_CASE("write_annotation_jsonld: IRIs that JSON-LD keeps as they are", "[ontology][jsonld]") {
    SmallAnnotationCase c;
    // A term followed by "//" is never a compact IRI; schemes that are no term are kept.
    for (const std::string base : {"schema://example.org/vase/", "urn:example:vase/",
                                   "tag:example.org,2026:vase#", "Oa:vase/"}) {
        INFO(base);
        c.doc.base_iri = base;
        const Json page = Json::parse(jsonld(c.doc));
        const std::string B = run_names(c.doc).base;
        CHECK(B.rfind(base + "run/", 0) == 0);
        CHECK(page["id"] == B + "annotations");
        CHECK(page["items"][1]["target"]["hasTexel"][0]["id"] == B + "texel/1");
        CHECK(page["items"][3]["target"]["id"] == B + "texel/1");
        CHECK(page["items"][3]["target"]["source"] == base + "mesh");
    }
}

TEST_CASE("write_annotation_jsonld: a run without texels is an empty page", "[ontology][jsonld]") {
    SmallAnnotationCase c;
    c.seg.texels.clear();
    c.seg.face_texel.assign(16, -1);
    c.seg.texel_texture.clear();
    c.seg.features.values.resize(0, kNumFeatures);
    c.seg.num_textures = 0;
    c.seg.texture_orientation.clear();
    c.descriptions.clear();
    const Json page = Json::parse(jsonld(c.doc));
    CHECK(page["type"] == "AnnotationPage");
    CHECK(page["items"] == Json::array());
}

TEST_CASE("write_annotation_jsonld: deterministic", "[ontology][jsonld]") {
    SmallAnnotationCase a;
    a.doc.include_dictionary = true;
    const std::string first = jsonld(a.doc);
    CHECK(jsonld(a.doc) == first);
    SmallAnnotationCase b;  // another document with equal content, at other addresses
    b.doc.include_dictionary = true;
    CHECK(jsonld(b.doc) == first);
    // Labels are written in the order of their language tags, whatever the insertion order.
    b.dictionary.concepts[0].labels.clear();
    b.dictionary.concepts[0].labels["fr"] = "forme circulaire";
    b.dictionary.concepts[0].labels["en"] = "circular shape";
    CHECK(jsonld(b.doc) == first);
}

TEST_CASE("write_annotation_jsonld: a failing stream is an IoError", "[ontology][jsonld]") {
    SmallAnnotationCase c;
    std::ofstream closed;  // never opened: every write fails
    REQUIRE_THROWS_AS(write_annotation_jsonld(closed, c.doc), IoError);
    struct FailingBuffer : std::streambuf {
        int overflow(int) override { return traits_type::eof(); }
        std::streamsize xsputn(const char*, std::streamsize) override { return 0; }
    } buffer;
    std::ostream throwing(&buffer);
    throwing.exceptions(std::ios::badbit);
    REQUIRE_THROWS_AS(write_annotation_jsonld(throwing, c.doc), IoError);
}
