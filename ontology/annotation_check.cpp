#include <cmath>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "ontology/detail/annotation_document.hpp"
#include "ontology/rdf_lexical.hpp"

// The checks of an annotation document before any triple is written: every part present,
// every table consistent with the mesh and the dictionary, every parameter in the range that
// shapes.ttl states. A document that passes gives a graph that conforms to the shapes.

namespace geotex {

using namespace rdf_detail;

namespace {

/// The ranges that shapes.ttl states for the parameter set, so that no output breaks them.
void check_parameters(const AnnotationDocument& doc, const Segmentation& seg,
                      const std::string& stage) {
    try {
        check_segmentation_params(doc.params);  // the pipeline's own ranges
    } catch (const InvalidInput& e) {
        throw InvalidInput(stage + ": " + e.what());
    }
    const auto in = [](double v, double lo, double hi) { return v >= lo && v <= hi; };
    std::string bad;
    if (!(seg.radius > 0) || !std::isfinite(seg.radius))
        bad = "the segmentation's radius is not positive";
    else if (doc.description.max_concepts < 0)
        bad = "max_concepts negative";
    else if (!(doc.description.max_significance >= 0) ||
             !std::isfinite(doc.description.max_significance))
        bad = "max_significance negative or not finite";
    else if (!in(doc.description.min_agreement, 0, 1))
        bad = "min_agreement not in [0, 1]";
    else if (!in(doc.description.min_stability, 0, 1))
        bad = "min_stability not in [0, 1]";
    else if (doc.description.num_resamples < 0)
        bad = "num_resamples < 0 (0: no stability test)";
    if (!bad.empty()) throw InvalidInput(stage + ": parameters: " + bad);
}

}  // namespace

Document rdf_detail::checked_document(const AnnotationDocument& doc, const std::string& stage) {
    if (!doc.segmentation || !doc.descriptions || !doc.dictionary || !doc.mesh)
        throw InvalidInput(stage +
                           ": the document needs its mesh, segmentation, texture "
                           "descriptions and dictionary");
    Document d{doc, *doc.segmentation, *doc.descriptions, *doc.dictionary, *doc.mesh, {}, {}};
    const std::string base = doc.base_iri.empty() ? std::string() : validate_base_iri(doc.base_iri);
    if (!doc.object_iri.empty()) validate_iri(doc.object_iri, "object IRI");
    if (!doc.creator_iri.empty()) validate_iri(doc.creator_iri, "creator IRI");
    d.dictionary_ns = checked_namespace(d.dictionary);
    check_concepts(d.dictionary);
    if (doc.mesh_file.empty()) throw InvalidInput(stage + ": the mesh file name is empty");
    if (doc.mesh_format.empty()) throw InvalidInput(stage + ": the mesh format is empty");
    if (doc.software_version.empty()) throw InvalidInput(stage + ": the software version is empty");
    check_language(doc.label_language, "label_language");
    check_sha256(doc.mesh_sha256, "the mesh digest");
    if (!(doc.unit_scale > 0) || !std::isfinite(doc.unit_scale))
        throw InvalidInput(stage + ": unit_scale must be positive and finite, not " +
                           std::to_string(doc.unit_scale));
    if (d.mesh.num_faces() == 0) throw InvalidInput(stage + ": the mesh has no face");
    check_parameters(doc, d.seg, stage);
    check_sha256(d.dictionary.sha256, "dictionary '" + d.dictionary.id + "' digest");
    d.names = names_of(doc, d.seg, base);
    if (doc.max_literal_faces < 0)
        throw InvalidInput(stage + ": max_literal_faces must be >= 0, not " +
                           std::to_string(doc.max_literal_faces));
    if (!doc.timestamp.empty()) {
        if (!is_date_time(doc.timestamp))
            throw InvalidInput(stage + ": timestamp '" + doc.timestamp.substr(0, 60) +
                               "' is not an xsd:dateTime (e.g. 2026-11-25T18:00:00Z)");
    }
    const Segmentation& seg = d.seg;
    const int num_faces = d.mesh.num_faces();
    const std::size_t num_texels = seg.texels.size();
    if (seg.face_texel.size() != static_cast<std::size_t>(num_faces))
        throw InvalidInput(stage + ": the segmentation has " +
                           std::to_string(seg.face_texel.size()) + " faces, the mesh " +
                           std::to_string(num_faces) + "; pass the mesh it was computed on");
    if (seg.texel_texture.size() != num_texels ||
        static_cast<std::size_t>(seg.features.values.rows()) != num_texels ||
        seg.features.values.cols() != kNumFeatures)
        throw InvalidInput(stage + ": the segmentation's texel tables disagree (" +
                           std::to_string(num_texels) + " texels, " +
                           std::to_string(seg.texel_texture.size()) + " texture labels, " +
                           std::to_string(seg.features.values.rows()) + " by " +
                           std::to_string(seg.features.values.cols()) + " features)");
    if (seg.num_textures < 0 ||
        seg.texture_orientation.size() != static_cast<std::size_t>(seg.num_textures) ||
        d.descriptions.size() != static_cast<std::size_t>(seg.num_textures))
        throw InvalidInput(stage + ": " + std::to_string(seg.num_textures) + " textures but " +
                           std::to_string(seg.texture_orientation.size()) + " orientations and " +
                           std::to_string(d.descriptions.size()) + " descriptions");
    std::vector<int> texel_count(static_cast<std::size_t>(seg.num_textures), 0);
    for (std::size_t i = 0; i < num_texels; ++i) {
        const int k = seg.texel_texture[i];
        if (k < 0 || k >= seg.num_textures)
            throw InvalidInput(stage + ": texel " + std::to_string(i) + " has texture " +
                               std::to_string(k) + ", not in [0, " +
                               std::to_string(seg.num_textures) + ")");
        ++texel_count[static_cast<std::size_t>(k)];
        const auto& faces = seg.texels[i].faces;
        const std::string where = stage + ": texel " + std::to_string(i);
        if (faces.empty()) throw InvalidInput(where + " has no face");
        for (std::size_t j = 0; j < faces.size(); ++j) {
            const int f = faces[j];
            if (f < 0 || f >= num_faces)
                throw InvalidInput(where + " has face " + std::to_string(f) + " but the mesh has " +
                                   std::to_string(num_faces) + " faces");
            if (j > 0 && f <= faces[j - 1])
                throw InvalidInput(where + ": faces not strictly increasing (" +
                                   std::to_string(faces[j - 1]) + " then " + std::to_string(f) +
                                   ")");
            for (int v : d.mesh.faces[static_cast<std::size_t>(f)])
                if (v < 0 || v >= d.mesh.num_vertices())
                    throw InvalidInput(where + ": face " + std::to_string(f) + " has vertex " +
                                       std::to_string(v) + ", out of range");
        }
    }
    const DictionaryConcept* first = d.dictionary.concepts.data();
    const DictionaryConcept* last = first + d.dictionary.concepts.size();
    for (std::size_t k = 0; k < d.descriptions.size(); ++k) {
        const TextureDescription& t = d.descriptions[k];
        const std::string where = stage + ": description " + std::to_string(k);
        if (t.texture != static_cast<int>(k))
            throw InvalidInput(where + " is of texture " + std::to_string(t.texture));
        if (t.num_texels != texel_count[k] || t.num_texels == 0)
            throw InvalidInput(where + " counts " + std::to_string(t.num_texels) +
                               " texels, the segmentation " + std::to_string(texel_count[k]));
        if (t.features.size() != static_cast<std::size_t>(kNumFeatures))
            throw InvalidInput(where + " has " + std::to_string(t.features.size()) +
                               " features, not " + std::to_string(kNumFeatures));
        std::vector<char> seen(kNumFeatures, 0);
        for (const FeatureScore& f : t.features) {
            if (f.feature < 0 || f.feature >= kNumFeatures ||
                seen[static_cast<std::size_t>(f.feature)])
                throw InvalidInput(where + ": feature column " + std::to_string(f.feature) +
                                   " is out of range or repeated");
            seen[static_cast<std::size_t>(f.feature)] = 1;
            if (f.concept_ptr && (f.concept_ptr < first || f.concept_ptr >= last))
                throw InvalidInput(where + ": the concept of feature " +
                                   kFeatureIds[static_cast<std::size_t>(f.feature)] +
                                   " is not one of the document's dictionary");
            const std::string feature = kFeatureIds[static_cast<std::size_t>(f.feature)];
            if ((f.chosen || f.withheld) && !f.concept_ptr)
                throw InvalidInput(where + ": feature " + feature + " is " +
                                   (f.chosen ? "chosen" : "withheld") + " but has no concept");
            if (f.chosen && f.withheld)
                throw InvalidInput(where + ": feature " + feature + " is both chosen and withheld");
            // An engraving is never called a dome: a concept is asserted only of the details
            // its relief allows.
            if (f.chosen && !relief_allows(f.concept_ptr->relief, seg.texture_orientation[k]))
                throw InvalidInput(where + ": concept '" + f.concept_ptr->id + "' of feature " +
                                   feature + " is chosen for " +
                                   (seg.texture_orientation[k] == DetailOrientation::Positive
                                        ? "raised"
                                        : "engraved") +
                                   " details, which its relief excludes");
            if (!(f.agreement >= 0 && f.agreement <= 1) || !(f.stability >= 0 && f.stability <= 1))
                throw InvalidInput(where + ": feature " + feature + " has agreement " +
                                   std::to_string(f.agreement) + " and stability " +
                                   std::to_string(f.stability) + "; both are shares in [0, 1]");
            // Rank and significance are defined together (shapes.ttl checks it too).
            const bool defined = !std::isnan(f.significance);
            if (defined != (f.rank > 0) || f.rank < 0 || f.rank > kNumFeatures ||
                f.significance < 0)
                throw InvalidInput(where + ": feature " +
                                   kFeatureIds[static_cast<std::size_t>(f.feature)] + " has rank " +
                                   std::to_string(f.rank) + " and significance " +
                                   std::to_string(f.significance) + "; the rank is in [1, " +
                                   std::to_string(kNumFeatures) +
                                   "] exactly when the significance is a number >= 0");
        }
        for (int i : t.chosen)
            if (i < 0 || i >= kNumFeatures || !t.features[static_cast<std::size_t>(i)].chosen)
                throw InvalidInput(where + ": chosen index " + std::to_string(i) +
                                   " does not point at a chosen feature");
        for (int i : t.withheld)
            if (i < 0 || i >= kNumFeatures || !t.features[static_cast<std::size_t>(i)].withheld)
                throw InvalidInput(where + ": withheld index " + std::to_string(i) +
                                   " does not point at a withheld feature");
    }
    return d;
}

}  // namespace geotex
