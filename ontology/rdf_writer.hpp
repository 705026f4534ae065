#pragma once
/// RDF output of geotex (Raptor2 serialisers): the annotation of one mesh as described in
/// ontology/README.md, and a dictionary as a SKOS concept scheme.

#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "geometry/segmentation.hpp"

namespace geotex {

enum class RdfFormat { Turtle, NTriples, RdfXml };

/// The geotex vocabulary namespace.
inline constexpr const char* kGeotexNs = "https://w3id.org/geotex/ns#";

/// Everything the annotation writer needs, as plain data.
struct AnnotationDocument {
    std::string base_iri;      ///< absolute IRI ending in '/' or '#' (validate_base_iri)
    std::string mesh_file;     ///< file name as given (dcterms:identifier; any characters)
    std::string mesh_format;   ///< "ply-binary-le", ... (dcterms:format)
    std::string mesh_sha256;   ///< hex digest of the mesh file bytes
    double unit_scale = 1;     ///< factor to the unit largest bounding-box side
    SegmentationParams params; ///< as used
    DescriptionParams description;
    std::string software_version;
    std::string timestamp;     ///< xsd:dateTime for prov:endedAtTime; empty: none (default,
                               ///< keeps the output byte-identical)
    std::string label_language = "en";  ///< language of rdfs:label of textures (from the
                                        ///< dictionary labels)
    bool include_dictionary = false;  ///< also write the dictionary's concept scheme (labels,
                                      ///< bounds, rules), so that one file answers queries on
                                      ///< concept labels
    int max_literal_faces = 200000;     ///< a texel with more faces is described by count
                                        ///< and digest only (faces left to the PLY)
    const Mesh* mesh = nullptr;  ///< the mesh the segmentation was computed on (vertex count,
                                 ///< texel centroids)
    const Segmentation* segmentation = nullptr;
    const std::vector<TextureDescription>* descriptions = nullptr;  ///< one per texture
    const Dictionary* dictionary = nullptr;
};

/// Writes the annotation graph. Deterministic: same document, same bytes. Throws
/// InvalidInput on a missing part or bad base IRI, IoError if Raptor2 fails.
void write_annotation_rdf(std::ostream& out, const AnnotationDocument& doc, RdfFormat format);

/// Writes the dictionary as a skos:ConceptScheme (concepts with labels, notation, feature,
/// bounds as xsd:decimal, and a sh:PropertyShape rule per concept).
void write_dictionary_rdf(std::ostream& out, const Dictionary& dictionary, RdfFormat format);

/// Checks that `iri` is an absolute IRI (scheme ":" ...) without characters that IRIs forbid
/// (space, <, >, ", {, }, |, \, ^, `, control characters), without a "." or ".." path segment
/// (readers resolve those away) and ending in '/' or '#'; returns it. Throws InvalidInput
/// naming the offending character or segment and its position.
std::string validate_base_iri(std::string_view iri);

/// The checks of validate_base_iri but the trailing '/' or '#': for IRIs used whole, such as
/// a named graph. `kind` names the IRI in messages ("graph IRI"). Throws InvalidInput.
std::string validate_iri(std::string_view iri, const std::string& kind = "IRI");

/// "urn:sha256:<hex>/": the base IRI used when the user gives none.
std::string default_base_iri(const std::string& sha256_hex);

/// Sorted, 0-based inclusive face ranges, e.g. "812-840 902 1100-1133" (gtx:faceRanges).
std::string face_ranges(const std::vector<int>& sorted_faces);

}  // namespace geotex
