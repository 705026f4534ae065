#pragma once
/// RDF output of geotex (Raptor2 serialisers): the annotation of one mesh as described in
/// ontology/README.md, and a dictionary as a SKOS concept scheme.

#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"
#include "geometry/segmentation.hpp"

namespace geotex {

struct ScaleChoice;  // geometry/scale_series.hpp
struct DetailLevel;  // geometry/scale_levels.hpp

enum class RdfFormat { Turtle, NTriples, RdfXml };

/// The geotex vocabulary namespace.
inline constexpr const char* kGeotexNs = "https://w3id.org/geotex/ns#";

/// The unit of the mesh's coordinates, when the user knows it (--mesh-unit): features with a
/// length or area dimension are then also given in that unit, with QUDT unit IRIs.
enum class MeshUnit { Unknown, Millimetre, Centimetre, Metre, Inch };

/// "mm", "cm", "m", "in" -> the unit; anything else: nullopt.
std::optional<MeshUnit> parse_mesh_unit(std::string_view text);
/// The short name ("mm", ...; "" for Unknown).
std::string mesh_unit_name(MeshUnit unit);

/// Everything the annotation writer needs, as plain data.
struct AnnotationDocument {
    /// The object's base IRI, ending in '/' or '#' (validate_base_iri): the mesh is
    /// `base_iri mesh` and the nodes of this run hang under `base_iri run/<run key>/`.
    /// Empty (the default): RFC 6920 hash names, the mesh `ni:///sha-256;<mesh digest>` and
    /// the run's nodes `ni:///sha-256;<run key>#...` (ontology/README.md, "IRIs").
    std::string base_iri;
    std::string object_iri;   ///< the physical object the mesh represents (CIDOC-CRM
                              ///< P138_represents, Linked Art); empty: none said
    std::string creator_iri;  ///< dcterms:creator of the annotations; empty: none
    MeshUnit mesh_unit = MeshUnit::Unknown;
    std::string mesh_file;      ///< file name as given (dcterms:identifier; any characters)
    std::string mesh_format;    ///< "ply-binary-le", ... (gtx:fileFormat; dc:format is its
                                ///< media type when one is registered)
    std::string mesh_sha256;    ///< hex digest of the mesh file bytes
    double unit_scale = 1;      ///< factor to the unit largest bounding-box side
    SegmentationParams params;  ///< as used
    DescriptionParams description;
    std::string software_version;
    std::string timestamp;  ///< xsd:dateTime for prov:endedAtTime; empty: none (default,
                            ///< keeps the output byte-identical)
    std::string label_language = "en";  ///< language of rdfs:label of textures (from the
                                        ///< dictionary labels)
    bool include_dictionary = false;    ///< also write the dictionary's concept scheme (labels,
                                        ///< bounds, rules), so that one file answers queries on
                                        ///< concept labels
    int max_literal_faces = 200000;     ///< a texel with more faces is described by count
                                        ///< and digest only (faces left to the PLY)
    const Mesh* mesh = nullptr;  ///< the mesh the segmentation was computed on (vertex count,
                                 ///< texel centroids)
    const Segmentation* segmentation = nullptr;
    const std::vector<TextureDescription>* descriptions = nullptr;  ///< one per texture
    const Dictionary* dictionary = nullptr;
    /// How params.radius_rel was chosen (`--scale auto`), or nullptr: given by the user.
    const ScaleChoice* scale_choice = nullptr;
    /// --levels: every level of detail, fine to coarse, the main one being `segmentation`
    /// (segment_levels), and the descriptions of each level's textures (empty for the main
    /// level); nullptr: one level. Needs scale_choice.
    const std::vector<DetailLevel>* levels = nullptr;
    const std::vector<std::vector<TextureDescription>>* level_descriptions = nullptr;
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

/// The names of one run (ontology/README.md, "IRIs"): the same document gives the same
/// names; a change of the mesh, of any option, of the dictionary, of the geotex version, of
/// the mesh unit, of the creator or of the timestamp gives another run key.
struct RunNames {
    std::string key;   ///< hexadecimal SHA-256 of the run's canonical description (gtx:runKey)
    std::string mesh;  ///< the mesh's IRI: the same for every run of the mesh (and base)
    std::string base;  ///< the prefix of every node of the run, ending in '/' or '#'
};

/// The names of the run that `doc` describes. Throws InvalidInput as write_annotation_rdf
/// does for a document it refuses.
RunNames run_names(const AnnotationDocument& doc);

/// The IRI of the software agent of a geotex version: one per version, not per run.
std::string software_iri(const std::string& version);

/// Sorted, 0-based inclusive face ranges, e.g. "812-840 902 1100-1133" (gtx:faceRanges).
std::string face_ranges(const std::vector<int>& sorted_faces);

}  // namespace geotex
