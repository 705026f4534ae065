#pragma once
// The checked annotation document and the run's names, shared by the files of the annotation
// writer: annotation_check.cpp (the checks), run_names.cpp (the run key and IRIs) and
// rdf_writer.cpp (the triples). Internal to ontology/.

#include <string>
#include <vector>

#include "ontology/detail/rdf_graph.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::rdf_detail {

/// An annotation document whose parts are all present and consistent (checked_document).
struct Document {
    const AnnotationDocument& doc;
    const Segmentation& seg;
    const std::vector<TextureDescription>& descriptions;
    const Dictionary& dictionary;
    const Mesh& mesh;
    RunNames names;  ///< names.base: the prefix of the run's nodes; names.mesh: the mesh
    std::string dictionary_ns;
};

/// Checks every part of `doc` that the graph states (parameters, segmentation, descriptions,
/// IRIs) and names the run. Throws InvalidInput with messages starting with `stage`.
Document checked_document(const AnnotationDocument& doc, const std::string& stage);

/// The run's names: the run key over everything that decides the run's triples, the mesh's
/// IRI and the prefix of the run's nodes, under `base` (validated) or as ni: hash names.
RunNames names_of(const AnnotationDocument& doc, const Segmentation& seg, const std::string& base);

/// The parameters of the run (gtx:ParameterSet) as triples of node `parameters`. One function
/// for the graph and for the run key, so that every parameter the output states also tells
/// runs apart.
void emit_parameters(Graph& g, const std::string& parameters, const AnnotationDocument& doc,
                     const Segmentation& seg);

/// How the scale was chosen (`--scale auto`, docs/scales.md): node `parameters`/scale-choice,
/// its rule's settings and one gtx:ScaleCandidate per scale of the series.
void emit_scale_choice(Graph& g, const std::string& parameters, const ScaleChoice& choice);

/// The QUDT unit of length (power 1) or area (power 2) in `u`.
std::string unit_iri(MeshUnit u, int power);

}  // namespace geotex::rdf_detail
