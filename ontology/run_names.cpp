#include <string>
#include <string_view>

#include "annotation/digest.hpp"
#include "geometry/scale_series.hpp"
#include "ontology/detail/annotation_document.hpp"
#include "ontology/detail/annotation_graph.hpp"
#include "ontology/detail/triple_sink.hpp"
#include "ontology/rdf_lexical.hpp"

// The names of a run (ontology/README.md, "IRIs"): the run key, the ni: or base-relative IRIs
// of the mesh and of the run's nodes, the software's IRI, and the mesh units.

namespace geotex {

using namespace rdf_detail;

// Curvatures (negative powers)
/// stay on the unit-side mesh: QUDT's reciprocal units are not all defined for every unit here.
std::string rdf_detail::unit_iri(MeshUnit u, int power) {
    const char* base = u == MeshUnit::Millimetre   ? "MilliM"
                       : u == MeshUnit::Centimetre ? "CentiM"
                       : u == MeshUnit::Metre      ? "M"
                                                   : "IN";
    return unit(base) + (power == 2 ? "2" : "");
}

void rdf_detail::emit_parameters(Graph& g, const std::string& parameters,
                                 const AnnotationDocument& doc, const Segmentation& seg) {
    const SegmentationParams& p = doc.params;
    g.type(parameters, gtx("ParameterSet"));
    g.type(parameters, prov("Entity"));
    if (!(p.radius > 0)) g.dbl(parameters, gtx("scale"), p.radius_rel, "radius_rel");
    g.dbl(parameters, gtx("radius"), seg.radius, "the radius");
    g.iri(parameters, gtx("orientation"),
          gtx(p.orientation == OrientationMode::Positive   ? "PositiveDetails"
              : p.orientation == OrientationMode::Negative ? "NegativeDetails"
                                                           : "BothDetails"));
    g.text(parameters, gtx("smoothing"), name_of(p.smoothing), "smoothing");
    g.boolean(parameters, gtx("areaWeighted"), p.area_weighted);
    g.text(parameters, gtx("discMeans"), name_of(p.disc), "disc");
    g.dbl(parameters, gtx("curvatureScale"), p.curvature_scale, "curvature_scale");
    g.dbl(parameters, gtx("mergeOverlap"), p.merge_overlap, "merge_overlap");
    g.dbl(parameters, gtx("minDepth"), p.min_depth_rel, "min_depth_rel");
    g.integer(parameters, gtx("minFaces"), p.min_faces);
    g.integer(parameters, gtx("neighbourRank"), p.clustering.neighbour_rank);
    g.integer(parameters, gtx("maxTextures"), p.clustering.max_clusters);
    g.dbl(parameters, gtx("qualityTolerance"), p.clustering.quality_tolerance, "quality_tolerance");
    g.dbl(parameters, gtx("minQuality"), p.clustering.min_quality, "min_quality");
    g.dbl(parameters, gtx("maxConductance"), p.clustering.max_conductance, "max_conductance");
    g.integer(parameters, gtx("clusterLandmarks"), p.clustering.max_points);
    const DescriptionParams& dp = doc.description;
    if (dp.max_concepts > 0) g.integer(parameters, gtx("maxConcepts"), dp.max_concepts);
    g.dbl(parameters, gtx("maxSignificance"), dp.max_significance, "max_significance");
    g.dbl(parameters, gtx("minAgreement"), dp.min_agreement, "min_agreement");
    g.dbl(parameters, gtx("minStability"), dp.min_stability, "min_stability");
    g.integer(parameters, gtx("resamples"), dp.num_resamples);
    if (doc.mesh_unit != MeshUnit::Unknown)
        g.iri(parameters, gtx("meshUnit"), unit_iri(doc.mesh_unit, 1));
    if (doc.scale_choice != nullptr) emit_scale_choice(g, parameters, *doc.scale_choice);
    if (doc.levels != nullptr) g.boolean(parameters, gtx("detailLevels"), true);
}

// `--scale auto` (docs/scales.md): the scale was chosen from a series; the choice and every
// scale of the series, with the counts that decided it, so that a reader can see how.
void rdf_detail::emit_scale_choice(Graph& g, const std::string& parameters,
                                   const ScaleChoice& choice) {
    const std::string node = parameters + "/scale-choice";
    g.iri(parameters, gtx("scaleChoice"), node);
    g.type(node, gtx("ScaleChoice"));
    g.boolean(node, gtx("stableScaleFound"), choice.stable);
    g.dbl(node, gtx("matchOverlap"), choice.params.match_iou, "match_iou");
    g.dbl(node, gtx("stableFraction"), choice.params.stable_fraction, "stable_fraction");
    g.dbl(node, gtx("minRadiusEdges"), choice.params.min_radius_edges, "min_radius_edges");
    g.dbl(node, gtx("nearMostFraction"), choice.params.near_most, "near_most");
    const auto& steps = choice.series.steps;
    for (std::size_t k = 0; k < steps.size(); ++k) {
        const ScaleStep& s = steps[k];
        const std::string candidate = scale_candidate_iri(parameters, k);
        g.iri(node, gtx("candidate"), candidate);
        if (static_cast<int>(k) == choice.chosen) g.iri(node, gtx("chosenCandidate"), candidate);
        g.type(candidate, gtx("ScaleCandidate"));
        g.dbl(candidate, gtx("candidateScale"), s.radius_rel, "scale");
        g.boolean(candidate, gtx("scaleSkipped"), s.skipped);
        if (s.skipped) continue;
        g.integer(candidate, gtx("texelsFound"), s.texels);
        g.integer(candidate, gtx("persistentTexels"), s.persistent);
        g.dbl(candidate, gtx("scaleStability"), s.stability, "stability");
        g.boolean(candidate, gtx("stableScale"), s.stable);
    }
}

namespace {

/// Collects the predicate and object of each triple as one line: the canonical text of the
/// parameter set that goes into the run key.
class KeyTextSink : public TripleSink {
  public:
    std::string text;
    void add(const std::string&, const std::string& predicate, const Term& object) override {
        text += predicate + ' ' + object.value + ' ' + object.datatype + '\n';
    }
};

}  // namespace

/// The run key hashes everything that decides the triples of the run's nodes; the object IRI
/// is not in it (it is said of the mesh, whose IRI does not depend on the run).
RunNames rdf_detail::names_of(const AnnotationDocument& doc, const Segmentation& seg,
                              const std::string& base) {
    KeyTextSink parameters;
    Graph g(parameters);
    emit_parameters(g, "p", doc, seg);
    const std::string text = "geotex run key 1\nsoftware " + doc.software_version + "\nmesh " +
                             doc.mesh_sha256 + "\ndictionary " + doc.dictionary->sha256 +
                             "\ncreator " + doc.creator_iri + "\ntimestamp " + doc.timestamp +
                             "\nmax_literal_faces " + std::to_string(doc.max_literal_faces) +
                             "\nlabel_language " + doc.label_language + "\n" + parameters.text;
    RunNames names;
    names.key = sha256_hex(text);
    if (base.empty()) {
        names.mesh = ni_name(doc.mesh_sha256);
        names.base = ni_name(names.key) + "#";
    } else {
        names.mesh = base + "mesh";
        names.base = base + "run/" + names.key.substr(0, 32) + "/";
    }
    return names;
}

std::optional<MeshUnit> parse_mesh_unit(std::string_view text) {
    if (text == "mm") return MeshUnit::Millimetre;
    if (text == "cm") return MeshUnit::Centimetre;
    if (text == "m") return MeshUnit::Metre;
    if (text == "in") return MeshUnit::Inch;
    return std::nullopt;
}

std::string mesh_unit_name(MeshUnit unit) {
    switch (unit) {
        case MeshUnit::Millimetre:
            return "mm";
        case MeshUnit::Centimetre:
            return "cm";
        case MeshUnit::Metre:
            return "m";
        case MeshUnit::Inch:
            return "in";
        case MeshUnit::Unknown:
            break;
    }
    return "";
}

std::string software_iri(const std::string& version) {
    return "https://w3id.org/geotex/release/" + iri_segment(version);
}

RunNames run_names(const AnnotationDocument& doc) {
    return rdf_detail::check_annotation_document(doc, "run_names").names;
}

// ---- shared with the JSON-LD writer (ontology/detail/annotation_graph.hpp) ------------------

std::string rdf_detail::texel_iri(const std::string& base, std::size_t texel) {
    return base + "texel/" + std::to_string(texel);
}
std::string rdf_detail::selector_iri(const std::string& base, std::size_t texel) {
    return texel_iri(base, texel) + "/faces";
}
std::string rdf_detail::texture_iri(const std::string& base, std::size_t texture) {
    return base + "texture/" + std::to_string(texture);
}
std::string rdf_detail::scale_candidate_iri(const std::string& parameters, std::size_t k) {
    return parameters + "/scale-choice/" + std::to_string(k);
}
std::string rdf_detail::annotation_iri(const std::string& base, std::size_t texture) {
    return base + "annotation/" + std::to_string(texture);
}
std::string rdf_detail::texel_annotation_iri(const std::string& base, std::size_t texel) {
    return texel_iri(base, texel) + "/annotation";
}
std::string rdf_detail::measurement_iri(const std::string& base, std::size_t texture, int feature) {
    return texture_iri(base, texture) + "/" +
           iri_segment(kFeatureIds[static_cast<std::size_t>(feature)]);
}
std::string rdf_detail::scheme_iri(const std::string& ns) { return ns + "scheme"; }
std::string rdf_detail::concept_iri(const std::string& ns, const DictionaryConcept& c) {
    return ns + iri_segment(c.id);
}
std::string rdf_detail::facet_iri(const std::string& ns, const DictionaryFacet& f) {
    return scheme_iri(ns) + "/facet/" + iri_segment(f.id);
}

}  // namespace geotex
