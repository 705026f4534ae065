#pragma once
// The IRIs and the checks of the annotation graph (ontology/README.md), shared by the RDF
// writer (rdf_writer.cpp) and the JSON-LD writer (jsonld_writer.cpp), so that both name every
// node the same way and refuse the same documents. Internal to ontology/.

#include <cstddef>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::rdf_detail {

// IRIs of a run under the prefix B of its nodes (RunNames::base; "Stable IRI patterns").
std::string texel_iri(const std::string& base, std::size_t texel);         ///< B texel/i
std::string selector_iri(const std::string& base, std::size_t texel);      ///< B texel/i/faces
std::string texture_iri(const std::string& base, std::size_t texture);     ///< B texture/k
std::string annotation_iri(const std::string& base, std::size_t texture);  ///< B annotation/k
/// B run/parameters/scale-choice/k: scale k of the series of `--scale auto`, whose node is
/// B run/parameters/scale-choice. `parameters` is the parameter set's IRI, B run/parameters.
std::string scale_candidate_iri(const std::string& parameters, std::size_t k);
/// B texel/i/annotation: the concepts that hold for the texel's own values.
std::string texel_annotation_iri(const std::string& base, std::size_t texel);
/// B texture/k/<feature id>; `feature` is a column of kFeatureIds.
std::string measurement_iri(const std::string& base, std::size_t texture, int feature);

// IRIs of a dictionary under its validated namespace N.
std::string scheme_iri(const std::string& ns);                               ///< N scheme
std::string concept_iri(const std::string& ns, const DictionaryConcept& c);  ///< N <id>
/// N scheme/facet/<id>: under the scheme's IRI, where no concept IRI can fall (a concept may
/// not be called "scheme"), so that no facet id collides with a concept or its interval.
std::string facet_iri(const std::string& ns, const DictionaryFacet& f);
/// N scheme/version/<version, percent-encoded>: the dictionary version that a run used
/// (prov:used) and that its interval nodes belong to.
std::string version_iri(const std::string& ns, const Dictionary& d);
/// N scheme/version/<version>/<concept id>: the concept's interval in that version.
std::string interval_iri(const std::string& ns, const Dictionary& d, const DictionaryConcept& c);
/// N scheme/version/<version>/<concept id>/rule: the interval as a SHACL property shape.
std::string interval_rule_iri(const std::string& ns, const Dictionary& d,
                              const DictionaryConcept& c);

/// The bodies of the annotation of texel `texel` (B texel/i/annotation), in the order of its
/// texture's chosen concepts: for each feature whose concept the texture asserts, the
/// dictionary concept whose interval holds the texel's OWN value of that feature, when there
/// is one and its relief allows the texel's orientation. So every body is true of the texel,
/// whatever the texture's mean. Empty: the texel gets no annotation. `doc` must have passed
/// check_annotation_document.
std::vector<const DictionaryConcept*> texel_concepts(const AnnotationDocument& doc,
                                                     std::size_t texel);
/// The same for texel `texel` of another segmentation of the document's mesh (a level of
/// detail, --levels) with the descriptions of its textures.
std::vector<const DictionaryConcept*> texel_concepts(
    const AnnotationDocument& doc, const Segmentation& seg,
    const std::vector<TextureDescription>& descriptions, std::size_t texel);

/// What an annotation document resolves to once checked.
struct CheckedAnnotation {
    RunNames names;             ///< the run key, the mesh's IRI and the prefix of the run's nodes
    std::string dictionary_ns;  ///< the validated namespace of the document's dictionary
};

/// Every check that write_annotation_rdf makes before its first byte: the document's parts,
/// base IRI, dictionary, parameters, segmentation and descriptions, then every string and
/// number of the graph (a dry run of the triples, the dictionary's included when
/// doc.include_dictionary). Throws InvalidInput; messages about the document start with
/// `stage` (the public function's name), those about one string with "RDF writer".
CheckedAnnotation check_annotation_document(const AnnotationDocument& doc,
                                            const std::string& stage);

}  // namespace geotex::rdf_detail
