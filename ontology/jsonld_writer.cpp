#include "ontology/jsonld_writer.hpp"

#include <algorithm>
#include <exception>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "ontology/detail/annotation_graph.hpp"
#include "ontology/rdf_lexical.hpp"

namespace geotex {

namespace {

using namespace rdf_detail;
// Keys keep the order in which they are set, so that the bytes depend on the data alone.
using Json = nlohmann::ordered_json;

const std::string kStage = "write_annotation_jsonld";

/// The geotex part of the context: the gtx prefix and the terms for the properties that the
/// W3C context lacks. Only JSON-LD 1.0 features, so that 1.0 processors read it too; skos:
/// and rdf: are prefixes of the W3C context.
Json geotex_context() {
    Json c = Json::object();
    c["gtx"] = kGeotexNs;
    c["prefLabel"] = Json{{"@id", "skos:prefLabel"}, {"@container", "@language"}};
    c["describes"] = Json{{"@id", "gtx:describes"}, {"@type", "@id"}};
    c["justifiedBy"] = Json{{"@id", "gtx:justifiedBy"}, {"@type", "@id"}};
    c["hasTexel"] = Json{{"@id", "gtx:hasTexel"}, {"@type", "@id"}};
    // Scores as strings with the Turtle's lexical form: a JSON number would read back as
    // another lexical form (or as an xsd:integer for 1.0). The datatype in full: the
    // readers' copies of the W3C context do not all define xsd:.
    const std::string xsd_double = "http://www.w3.org/2001/XMLSchema#double";
    c["stability"] = Json{{"@id", "gtx:stability"}, {"@type", xsd_double}};
    c["agreement"] = Json{{"@id", "gtx:agreement"}, {"@type", xsd_double}};
    c["faceRanges"] = Json{{"@id", "rdf:value"}, {"@type", "gtx:faceRanges"}};
    c["facesSha256"] = "gtx:facesSha256";
    c["faceCount"] = "gtx:faceCount";  // a JSON integer reads as xsd:integer, as in the Turtle
    c["boundToMesh"] = "gtx:boundToMesh";
    return c;
}

/// Every term of http://www.w3.org/ns/anno.jsonld. A JSON-LD 1.0 processor expands "t:rest"
/// with any term t of the context as a compact IRI (1.1 only with prefix terms), so an IRI
/// whose scheme is one of these would be read as another IRI.
// clang-format off
constexpr std::string_view kWebAnnotationTerms[] = {
    "oa", "dc", "dcterms", "dctypes", "foaf", "rdf", "rdfs", "skos", "xsd", "iana", "owl",
    "as", "schema", "id", "type", "Annotation", "Dataset", "Image", "Video", "Audio", "Text",
    "TextualBody", "ResourceSelection", "SpecificResource", "FragmentSelector", "CssSelector",
    "XPathSelector", "TextQuoteSelector", "TextPositionSelector", "DataPositionSelector",
    "SvgSelector", "RangeSelector", "TimeState", "HttpRequestState", "CssStylesheet", "Choice",
    "Person", "Software", "Organization", "AnnotationCollection", "AnnotationPage", "Audience",
    "Motivation", "bookmarking", "classifying", "commenting", "describing", "editing",
    "highlighting", "identifying", "linking", "moderating", "questioning", "replying",
    "reviewing", "assessing", "tagging", "auto", "ltr", "rtl", "body", "target", "source",
    "selector", "state", "scope", "refinedBy", "startSelector", "endSelector", "renderedVia",
    "creator", "generator", "rights", "homepage", "via", "canonical", "stylesheet", "cached",
    "conformsTo", "items", "partOf", "first", "last", "next", "prev", "audience", "motivation",
    "purpose", "textDirection", "accessibility", "bodyValue", "format", "language",
    "processingLanguage", "value", "exact", "prefix", "suffix", "styleClass", "name", "email",
    "email_sha1", "nickname", "label", "created", "modified", "generated", "sourceDate",
    "sourceDateStart", "sourceDateEnd", "start", "end", "total", "startIndex"};
// clang-format on

/// Throws InvalidInput when JSON-LD would read `iri` (absolute, validated) as a compact IRI.
void check_not_compact_iri(const std::string& iri, const Json& context, const std::string& what) {
    const std::size_t colon = iri.find(':');
    const std::string scheme = iri.substr(0, colon);
    if (iri.compare(colon + 1, 2, "//") == 0) return;  // "t://..." is never a compact IRI
    const bool term = context.contains(scheme) ||
                      std::find(std::begin(kWebAnnotationTerms), std::end(kWebAnnotationTerms),
                                scheme) != std::end(kWebAnnotationTerms);
    if (term)
        throw InvalidInput(kStage + ": " + what + " '" + iri.substr(0, 200) + "' starts with '" +
                           scheme +
                           ":', a term of the JSON-LD context, so JSON-LD readers would take "
                           "it for a compact IRI and expand it into another IRI; use another "
                           "scheme (e.g. https: or urn:)");
}

/// One texel as an oa:SpecificResource of the mesh, with its face selector.
Json texel_target(const AnnotationDocument& doc, const RunNames& names, std::size_t i) {
    const std::string& base = names.base;
    const std::vector<int>& faces = doc.segmentation->texels[i].faces;
    Json selector = Json::object();
    selector["id"] = selector_iri(base, i);
    selector["type"] = "gtx:FaceSetSelector";
    selector["conformsTo"] = "gtx:FaceSetSelectorSpec";
    const std::string ranges = face_ranges(faces);
    const long long num_faces = static_cast<long long>(faces.size());
    // The same cap as the Turtle: above it, the digest of the ranges instead of the ranges.
    if (num_faces <= doc.max_literal_faces)
        selector["faceRanges"] = ranges;
    else
        selector["facesSha256"] = sha256_hex(ranges);
    selector["faceCount"] = num_faces;
    selector["boundToMesh"] = doc.mesh_sha256;

    Json target = Json::object();
    target["id"] = texel_iri(base, i);
    target["type"] = Json::array({"SpecificResource", "gtx:Texel"});
    target["source"] = names.mesh;
    target["selector"] = std::move(selector);
    return target;
}

/// A chosen concept as a body: its IRI, or with the dictionary in the graph, the concept with
/// its labels (a language map, one label per language).
Json concept_body(const DictionaryConcept& c, const std::string& ns, bool with_dictionary) {
    if (!with_dictionary) return concept_iri(ns, c);
    Json body = Json::object();
    body["id"] = concept_iri(ns, c);
    body["type"] = "skos:Concept";
    if (!c.labels.empty()) {
        Json labels = Json::object();
        for (const auto& [lang, label] : c.labels) labels[lang] = label;
        body["prefLabel"] = std::move(labels);
    }
    return body;
}

/// The Web Annotation provenance, as in the Turtle: the software (one IRI per geotex version)
/// as generator, the user's creator, the time only when asked for.
void add_authorship(Json& annotation, const AnnotationDocument& doc) {
    annotation["generator"] =
        Json{{"id", software_iri(doc.software_version)}, {"type", "Software"}};
    if (!doc.creator_iri.empty()) annotation["creator"] = doc.creator_iri;
    if (!doc.timestamp.empty()) annotation["created"] = doc.timestamp;
}

Json annotation_page(const AnnotationDocument& doc, const CheckedAnnotation& checked,
                     const Json& context) {
    const std::string& B = checked.names.base;
    const Segmentation& seg = *doc.segmentation;
    const std::vector<TextureDescription>& descriptions = *doc.descriptions;

    std::vector<std::vector<std::size_t>> texels_of(descriptions.size());
    for (std::size_t i = 0; i < seg.texels.size(); ++i)
        texels_of[static_cast<std::size_t>(seg.texel_texture[i])].push_back(i);

    // One annotation per texture, its target the texture as a whole, then one per texel that
    // some concept holds for, its target the texel alone (ontology/README.md).
    Json items = Json::array();
    for (std::size_t k = 0; k < descriptions.size(); ++k) {
        const TextureDescription& t = descriptions[k];
        Json annotation = Json::object();
        annotation["id"] = annotation_iri(B, k);
        annotation["type"] = "Annotation";
        annotation["motivation"] = "classifying";
        // Bodies in the order of the Turtle's texture label: most significant first.
        double stability = 1, agreement = 1;
        if (!t.chosen.empty()) {
            Json bodies = Json::array();
            for (int i : t.chosen) {
                const FeatureScore& f = t.features[static_cast<std::size_t>(i)];
                bodies.push_back(
                    concept_body(*f.concept_ptr, checked.dictionary_ns, doc.include_dictionary));
                stability = std::min(stability, f.stability);
                agreement = std::min(agreement, f.agreement);
            }
            annotation["body"] = std::move(bodies);
        }
        Json texels = Json::array();
        for (std::size_t i : texels_of[k]) texels.push_back(texel_target(doc, checked.names, i));
        Json target = Json::object();
        target["id"] = texture_iri(B, k);
        target["type"] = Json::array({"SpecificResource", "gtx:GeometricTexture"});
        target["source"] = checked.names.mesh;
        target["hasTexel"] = std::move(texels);
        annotation["target"] = std::move(target);
        annotation["describes"] = texture_iri(B, k);
        if (!t.chosen.empty()) {
            Json measurements = Json::array();
            for (int i : t.chosen)
                measurements.push_back(
                    measurement_iri(B, k, t.features[static_cast<std::size_t>(i)].feature));
            annotation["justifiedBy"] = std::move(measurements);
            // The weakest body's scores, as in the Turtle.
            annotation["stability"] = double_lexical(stability, "stability");
            annotation["agreement"] = double_lexical(agreement, "agreement");
        }
        add_authorship(annotation, doc);
        items.push_back(std::move(annotation));
    }
    for (std::size_t i = 0; i < seg.texels.size(); ++i) {
        const std::vector<const DictionaryConcept*> concepts = texel_concepts(doc, i);
        if (concepts.empty()) continue;
        Json annotation = Json::object();
        annotation["id"] = texel_annotation_iri(B, i);
        annotation["type"] = Json::array({"Annotation", "gtx:TexelAnnotation"});
        annotation["motivation"] = "classifying";
        Json bodies = Json::array();
        for (const DictionaryConcept* c : concepts)
            bodies.push_back(concept_body(*c, checked.dictionary_ns, doc.include_dictionary));
        annotation["body"] = std::move(bodies);
        // The whole texel again, so that each annotation reads alone in JSON.
        annotation["target"] = texel_target(doc, checked.names, i);
        add_authorship(annotation, doc);
        items.push_back(std::move(annotation));
    }

    Json page = Json::object();
    page["@context"] = Json::array({kWebAnnotationContext, context});
    page["id"] = B + "annotations";
    page["type"] = "AnnotationPage";
    page["items"] = std::move(items);
    return page;
}

}  // namespace

// The whole text is made before the first byte goes out, so that no error leaves half a
// document in the stream.
void write_annotation_jsonld(std::ostream& out, const AnnotationDocument& doc) {
    const CheckedAnnotation checked = check_annotation_document(doc, kStage);
    const Json context = geotex_context();
    check_not_compact_iri(checked.names.base, context, "base IRI");
    check_not_compact_iri(checked.names.mesh, context, "mesh IRI");
    if (!doc.creator_iri.empty()) check_not_compact_iri(doc.creator_iri, context, "creator IRI");
    check_not_compact_iri(checked.dictionary_ns, context,
                          "namespace of dictionary '" + doc.dictionary->id + "'");
    std::string text;
    try {
        text = annotation_page(doc, checked, context).dump(2) + "\n";
    } catch (const Json::exception& e) {
        // Every string was checked to be UTF-8 above; this guards that invariant.
        throw InvalidInput(kStage + ": " + e.what());
    }
    try {
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        out.flush();
    } catch (const std::exception&) {
        throw IoError(kStage + ": cannot write the output stream");
    }
    if (!out) throw IoError(kStage + ": cannot write the output stream");
}

}  // namespace geotex
