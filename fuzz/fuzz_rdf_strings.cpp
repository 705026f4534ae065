// libFuzzer target: the strings of the RDF writer. The input is a syntax byte followed by
// fields separated by 0xFF (a byte that never occurs in UTF-8, so no valid string is lost):
//
//   mesh file name, base IRI, label, language tag, concept id, dictionary namespace, text
//
// They go into a one-texel annotation document that also carries its dictionary (the text
// field is the software version, the mesh format, the dictionary title, and the concept's
// definition and source; the label is also the label of the concept's facet). When the writer
// accepts them, its output is read back with Raptor2's parser of the same syntax: no error, the
// same number of triples as with plain ASCII strings (nothing injected), and every string back byte
// for byte. InvalidInput is an answer.

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/segmentation.hpp"
#include "ontology/rdf_writer.hpp"
#include "tests/raptor_reader.hpp"

namespace {

using namespace geotex;
using geotex::test::ParsedTriple;
using geotex::test::RaptorReading;
using geotex::test::read_with_raptor;

/// The writer's output for the current input, shown when an invariant breaks.
std::string current_output;

void require(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_rdf_strings: invariant broken: %s\n---- output:\n%s\n----\n", what,
                 current_output.c_str());
    std::abort();
}

const std::string kDcterms = "http://purl.org/dc/terms/";
const std::string kSkos = "http://www.w3.org/2004/02/skos/core#";
const std::string kRdfs = "http://www.w3.org/2000/01/rdf-schema#";
const std::string kOwl = "http://www.w3.org/2002/07/owl#";

/// The strings under test.
struct Strings {
    std::string mesh_file = "vase.ply";
    std::string base_iri = "https://example.org/objects/vase-42/";
    std::string label = "circular shape";
    std::string language = "en";
    std::string concept_id = "circular-shape";
    std::string namespace_iri = "https://example.org/dict#";
    std::string text = "plain text";
};

/// The fields of the input; an empty or missing field keeps its plain value, so that the
/// graph has the same shape whatever the strings.
Strings split(std::string_view input) {
    Strings s;
    std::string* fields[] = {&s.mesh_file,  &s.base_iri,      &s.label, &s.language,
                             &s.concept_id, &s.namespace_iri, &s.text};
    std::size_t i = 0;
    for (std::string* field : fields) {
        if (i > input.size()) break;
        std::size_t end = input.find('\xFF', i);
        if (end == std::string_view::npos) end = input.size();
        if (end > i) *field = std::string(input.substr(i, end - i));
        i = end + 1;
    }
    return s;
}

/// A two-face mesh with one texel (face 0) in one texture, described by two concepts: the
/// fuzzed one (contour_sphericity) and a plain one (area).
struct Case {
    Mesh mesh;
    Segmentation seg;
    Dictionary dictionary;
    std::vector<TextureDescription> descriptions;
    AnnotationDocument doc;

    explicit Case(const Strings& s) {
        mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
        mesh.faces = {{0, 1, 2}, {0, 2, 3}};
        seg.radius = 0.25;
        Texel texel;
        texel.faces = {0};
        seg.texels = {texel};
        seg.face_texel = {0, -1};
        seg.texel_texture = {0};
        seg.num_textures = 1;
        seg.texture_orientation = {DetailOrientation::Positive};
        seg.features.names.assign(kFeatureIds.begin(), kFeatureIds.end());
        seg.features.values = Eigen::MatrixXd::Constant(1, kNumFeatures, 0.5);

        dictionary.id = "fuzz";
        dictionary.version = "1";
        dictionary.namespace_iri = s.namespace_iri;
        dictionary.titles = {{s.language, s.text}};
        dictionary.sha256 = std::string(64, 'a');
        dictionary.source_name = "fuzz.yaml";
        dictionary.concepts.resize(2);
        DictionaryConcept& fuzzed = dictionary.concepts[0];
        fuzzed.id = s.concept_id;
        fuzzed.feature = static_cast<int>(Feature::ContourSphericity);
        fuzzed.upper = 1;
        fuzzed.upper_text = "1";
        fuzzed.labels = {{s.language, s.label}};
        fuzzed.definitions = {{s.language, s.text}};
        fuzzed.source = s.text;
        DictionaryConcept& plain = dictionary.concepts[1];
        plain.id = "small-area";
        plain.feature = static_cast<int>(Feature::Area);
        plain.lower = 0;
        plain.lower_text = "0";
        plain.upper = 1;
        plain.upper_text = "1";
        plain.labels = {{"en", "small area"}};
        // Declared facets go into the graph too: the fuzzed label is also the outline's.
        dictionary.declares_facets = true;
        DictionaryFacet outline;
        outline.id = "outline";
        outline.labels = {{s.language, s.label}};
        outline.features = {static_cast<int>(Feature::ContourSphericity)};
        DictionaryFacet size;
        size.id = "size";
        size.labels = {{"en", "size"}};
        size.features = {static_cast<int>(Feature::Area)};
        dictionary.facets = {outline, size};
        dictionary.feature_facet.assign(kNumFeatures, -1);
        dictionary.feature_facet[static_cast<std::size_t>(Feature::ContourSphericity)] = 0;
        dictionary.feature_facet[static_cast<std::size_t>(Feature::Area)] = 1;

        TextureDescription t;
        t.texture = 0;
        t.num_texels = 1;
        for (int j = 0; j < kNumFeatures; ++j) {
            FeatureScore f;
            f.feature = j;
            f.value = 0.5;
            f.significance = 0;
            f.rank = j + 1;
            t.features.push_back(f);
        }
        for (int j : {1, 4}) {  // contour_sphericity, area
            t.features[static_cast<std::size_t>(j)].concept_ptr =
                &dictionary.concepts[j == 1 ? 0 : 1];
            t.features[static_cast<std::size_t>(j)].chosen = true;
            t.features[static_cast<std::size_t>(j)].agreement = 1;
            t.features[static_cast<std::size_t>(j)].stability = 1;
            t.chosen.push_back(j);
        }
        descriptions = {t};

        doc.base_iri = s.base_iri;
        doc.mesh_file = s.mesh_file;
        doc.mesh_format = s.text;
        doc.mesh_sha256 = std::string(64, 'b');
        doc.software_version = s.text;
        doc.label_language = s.language;
        doc.description.max_concepts = 2;
        doc.include_dictionary = true;
        doc.mesh = &mesh;
        doc.segmentation = &seg;
        doc.descriptions = &descriptions;
        doc.dictionary = &dictionary;
    }

    Case(const Case&) = delete;
    Case& operator=(const Case&) = delete;
};

/// The one triple with subject `s` and predicate `p`; anything else is a finding.
const ParsedTriple& one(const RaptorReading& r, const std::string& s, const std::string& p,
                        const char* what) {
    const auto all = r.find(s, p);
    require(all.size() == 1, what);
    return *all.front();
}

/// Language tags compare case-insensitively (BCP 47); Raptor's RDF/XML parser lower-cases them.
bool same_language(const std::string& a, const std::string& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(a[i])) !=
            std::tolower(static_cast<unsigned char>(b[i])))
            return false;
    return true;
}

/// The Raptor2 parser that reads a syntax back. N-Triples is a subset of Turtle and goes
/// through the Turtle parser: Raptor 2.0.15's N-Triples parser leaks the datatype URI of every
/// typed literal, which would drown the leaks of the writer under test.
const char* parser_name(RdfFormat format) {
    return format == RdfFormat::RdfXml ? "rdfxml" : "turtle";
}

/// N-Triples proper: one triple per line, each ending in " .", no raw control character.
bool is_line_based(const std::string& text) {
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) return false;  // the last line ends with a line feed
        const std::string_view line(text.data() + start, end - start);
        if (line.size() < 2 || line.substr(line.size() - 2) != " .") return false;
        for (const char c : line)
            if (static_cast<unsigned char>(c) < 0x20 && c != '\t') return false;
        start = end + 1;
    }
    return true;
}

std::string write(const AnnotationDocument& doc, RdfFormat format) {
    std::ostringstream out;
    write_annotation_rdf(out, doc, format);
    return out.str();
}

/// Triples of the document with the plain strings, per syntax.
std::size_t plain_count(RdfFormat format) {
    static std::size_t counts[3] = {0, 0, 0};
    std::size_t& n = counts[static_cast<int>(format)];
    if (n == 0) {
        const Strings plain;
        Case c(plain);
        const RaptorReading p = read_with_raptor(write(c.doc, format), parser_name(format));
        require(p.errors.empty() && !p.triples.empty(), "the plain document reads back");
        n = p.triples.size();
    }
    return n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    // Turtle half of the time, N-Triples and RDF/XML a quarter each.
    const RdfFormat format = data[0] % 4 == 2   ? RdfFormat::NTriples
                             : data[0] % 4 == 3 ? RdfFormat::RdfXml
                                                : RdfFormat::Turtle;
    const Strings s = split(std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
    Case c(s);
    std::string text;
    try {
        c.doc.base_iri = validate_base_iri(s.base_iri);
        text = write(c.doc, format);
    } catch (const InvalidInput&) {
        return 0;
    }
    current_output = text;
    require(!text.empty(), "the writer wrote something");

    if (format == RdfFormat::NTriples) require(is_line_based(text), "N-Triples is line-based");
    const RaptorReading p = read_with_raptor(text, parser_name(format));
    require(p.errors.empty(), "the output parses without error");
    require(p.triples.size() == plain_count(format), "as many triples as with plain strings");

    const RunNames names = run_names(c.doc);
    const std::string& base = names.base;
    require(one(p, names.mesh, kDcterms + "identifier", "one mesh identifier").o == s.mesh_file,
            "the mesh file name comes back");
    require(
        one(p, names.mesh, std::string(kGeotexNs) + "fileFormat", "one mesh format").o == s.text,
        "the mesh format comes back");
    require(one(p, software_iri(s.text), kOwl + "versionInfo", "one version").o == s.text,
            "the software version comes back");

    // The texture label: both concepts are labelled in English only when the language is "en".
    const ParsedTriple& label = one(p, base + "texture/0", kRdfs + "label", "one texture label");
    require(label.o == s.label + ", small area", "the texture label comes back");
    require(same_language(label.language, s.language == "en" ? "en" : ""), "the label's language");

    const std::string& ns = c.dictionary.namespace_iri;
    const ParsedTriple& title = one(p, ns + "scheme", kSkos + "prefLabel", "one scheme title");
    require(title.o == s.text && same_language(title.language, s.language), "the title comes back");

    // The outline facet, under the scheme's IRI, with the fuzzed label.
    const std::string facet = ns + "scheme/facet/outline";
    const ParsedTriple& facet_label = one(p, facet, kSkos + "prefLabel", "one facet label");
    require(facet_label.o == s.label && same_language(facet_label.language, s.language),
            "the facet label comes back");

    // The fuzzed concept: the one subject whose notation is its id, in the namespace, but
    // the facets (whose ids are not fuzzed: "outline" may be the concept's id too).
    std::vector<const ParsedTriple*> notations;
    for (const ParsedTriple& t : p.triples)
        if (t.p == kSkos + "notation" && t.o == s.concept_id &&
            t.s.compare(0, ns.size() + 12, ns + "scheme/facet") != 0)
            notations.push_back(&t);
    require(notations.size() == 1, "one concept has the id as notation");
    const std::string& concept_iri = notations.front()->s;
    require(concept_iri.compare(0, ns.size(), ns) == 0 && concept_iri.size() > ns.size(),
            "the concept IRI is in the namespace");
    require(concept_iri.find_first_of("/#?", ns.size()) == std::string::npos,
            "the concept id adds no segment, query or fragment");
    const ParsedTriple& pref = one(p, concept_iri, kSkos + "prefLabel", "one concept label");
    require(pref.o == s.label && same_language(pref.language, s.language),
            "the concept label comes back");
    // Definition and source belong to the concept's interval in this version.
    const std::string interval =
        one(p, concept_iri, std::string(kGeotexNs) + "hasInterval", "one interval").o;
    require(interval.compare(0, ns.size() + 17, ns + "scheme/version/1/") == 0,
            "the interval is under the version's IRI");
    const ParsedTriple& definition = one(p, interval, kSkos + "definition", "one definition");
    require(definition.o == s.text && same_language(definition.language, s.language),
            "the definition comes back");
    require(one(p, interval, kDcterms + "source", "one source").o == s.text,
            "the source comes back");
    return 0;
}
