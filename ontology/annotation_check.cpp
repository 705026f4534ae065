#include <cmath>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/scale_levels.hpp"
#include "geometry/scale_series.hpp"
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

/// The texels, textures and words of one segmentation of `mesh` (the main one, or a level of
/// detail's): sizes, ids, faces and the concepts of `dictionary`.
void check_segmentation_words(const Segmentation& seg,
                              const std::vector<TextureDescription>& descriptions,
                              const Dictionary& dictionary, const Mesh& mesh,
                              const std::string& stage) {
    const int num_faces = mesh.num_faces();
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
        descriptions.size() != static_cast<std::size_t>(seg.num_textures))
        throw InvalidInput(stage + ": " + std::to_string(seg.num_textures) + " textures but " +
                           std::to_string(seg.texture_orientation.size()) + " orientations and " +
                           std::to_string(descriptions.size()) + " descriptions");
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
            for (int v : mesh.faces[static_cast<std::size_t>(f)])
                if (v < 0 || v >= mesh.num_vertices())
                    throw InvalidInput(where + ": face " + std::to_string(f) + " has vertex " +
                                       std::to_string(v) + ", out of range");
        }
    }
    const DictionaryConcept* first = dictionary.concepts.data();
    const DictionaryConcept* last = first + dictionary.concepts.size();
    for (std::size_t k = 0; k < descriptions.size(); ++k) {
        const TextureDescription& t = descriptions[k];
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
}

/// --levels: the levels hold one main level, each other level is a segmentation of the same
/// mesh with the words of its textures, and every part_of names a texel of the next level.
void check_levels(const Document& d, const std::string& stage) {
    const std::vector<DetailLevel>& levels = *d.doc.levels;
    if (d.doc.scale_choice == nullptr || d.doc.level_descriptions == nullptr ||
        d.doc.level_descriptions->size() != levels.size())
        throw InvalidInput(stage +
                           ": levels need the scale choice and one set of descriptions "
                           "per level");
    int mains = 0;
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const DetailLevel& level = levels[k];
        const std::string where = stage + ": level " + std::to_string(k);
        mains += level.main;
        if (level.step < 0 ||
            level.step >= static_cast<int>(d.doc.scale_choice->series.steps.size()))
            throw InvalidInput(where + ": its step is not one of the scale series");
        const Segmentation& seg = level_segmentation(levels, k, d.seg);
        if (!level.main)
            check_segmentation_words(seg, (*d.doc.level_descriptions)[k], d.dictionary, d.mesh,
                                     where);
        const std::size_t coarser =
            k + 1 < levels.size() ? level_segmentation(levels, k + 1, d.seg).texels.size() : 0;
        if (level.part_of.size() != seg.texels.size())
            throw InvalidInput(where + ": part_of is not one entry per texel");
        for (int c : level.part_of)
            if (c < -1 || c >= static_cast<int>(coarser))
                throw InvalidInput(where + ": part_of names texel " + std::to_string(c) +
                                   " of the next level, which has " + std::to_string(coarser));
    }
    if (mains != 1) throw InvalidInput(stage + ": the levels must hold one main level");
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
    check_segmentation_words(d.seg, d.descriptions, d.dictionary, d.mesh, stage);
    if (doc.levels != nullptr) check_levels(d, stage);
    return d;
}

}  // namespace geotex
