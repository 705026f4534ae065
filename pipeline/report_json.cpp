#include "pipeline/report_json.hpp"

#include <cmath>
#include <vector>

#include "annotation/texture_label.hpp"
#include "common/errors.hpp"
#include "pipeline/parameters_json.hpp"
#include "pipeline/scale_report.hpp"
#include "pipeline/texture_colour.hpp"

namespace geotex {

using Json = nlohmann::ordered_json;

namespace {

Json input_json(const ReportInput& in) {
    const MeshRepairReport& r = in.repair;
    Json j;
    j["file"] = in.file;
    j["format"] = in.format;
    j["input_vertices"] = r.num_input_vertices;
    j["input_polygons"] = r.num_input_polygons;
    Json repair;
    repair["polygons_triangulated"] = r.num_polygons_triangulated;
    repair["duplicate_vertices_merged"] = r.num_duplicate_vertices_merged;
    repair["degenerate_faces_removed"] = r.num_degenerate_faces_removed;
    repair["duplicate_faces_removed"] = r.num_duplicate_faces_removed;
    repair["faces_flipped"] = r.num_faces_flipped;
    repair["isolated_vertices"] = r.num_isolated_vertices;
    repair["boundary_edges"] = r.num_boundary_edges;
    repair["non_manifold_edges"] = r.num_non_manifold_edges;
    repair["components"] = r.num_components;
    repair["closed_components"] = r.num_closed_components;
    j["repair"] = repair;
    return j;
}

void check_sizes(const Segmentation& seg, const char* stage) {
    const auto refuse = [&](const std::string& what) {
        throw InvalidInput(std::string(stage) + ": " + what +
                           "; pass the result of run_segmentation as it is");
    };
    const std::size_t n = seg.texels.size();
    for (const DetailOrientation o : seg.runs)
        if (!(o == DetailOrientation::Positive ? seg.positive_depth : seg.negative_depth))
            refuse(std::string("no depth map for the ") + name_of(o) + " orientation it ran");
    if (seg.texel_sets.size() != seg.runs.size() || seg.clusterings.size() != seg.runs.size())
        refuse("not one texel set and one clustering per orientation run (" +
               std::to_string(seg.runs.size()) + " runs)");
    if (seg.texel_texture.size() != n ||
        seg.features.values.rows() != static_cast<Eigen::Index>(n) ||
        seg.features.values.cols() != kNumFeatures)
        refuse("texel_texture or the feature table is not one row per texel (" + std::to_string(n) +
               " texels)");
    if (seg.texture_orientation.size() != static_cast<std::size_t>(seg.num_textures))
        refuse("texture_orientation is not one entry per texture (" +
               std::to_string(seg.num_textures) + " textures)");
}

// Per texture of `descriptions` (the annotation's own, or a level's) its chosen and withheld
// concepts and every feature's numbers, labels in the annotation's language.
Json texture_words_json(const Annotation& a, const std::vector<TextureDescription>& descriptions) {
    const Dictionary& dictionary = *a.dictionary;
    const std::string& lang = a.options.label_language;
    Json textures = Json::array();
    const auto facet_of = [&](int facet) {
        return facet >= 0 && facet < static_cast<int>(dictionary.facets.size())
                   ? Json(dictionary.facets[static_cast<std::size_t>(facet)].id)
                   : Json(nullptr);
    };
    // One entry per concept the rule picked: its feature, facet and the numbers that made it.
    const auto concept_entry = [&](const FeatureScore& f) {
        return Json{{"feature", kFeatureIds[f.feature]},
                    {"concept", f.concept_ptr->id},
                    {"label", concepts_label({f.concept_ptr}, dictionary, lang).text},
                    {"facet", facet_of(f.facet)},
                    {"value", number_or_null(f.value)},
                    {"significance", number_or_null(f.significance)},
                    {"agreement", number_or_null(f.agreement)},
                    {"stability", number_or_null(f.stability)}};
    };
    for (const auto& d : descriptions) {
        Json t;
        t["texture"] = d.texture;
        t["texels"] = d.num_texels;
        t["orientation"] = d.orientation == DetailOrientation::Positive ? "positive" : "negative";
        Json chosen = Json::array();
        for (int i : d.chosen)
            chosen.push_back(concept_entry(d.features[static_cast<std::size_t>(i)]));
        t["concepts"] = chosen;
        Json withheld = Json::array();
        for (int i : d.withheld)
            withheld.push_back(concept_entry(d.features[static_cast<std::size_t>(i)]));
        t["withheld"] = withheld;
        Json features = Json::array();
        for (const auto& f : d.features)
            features.push_back(
                {{"feature", kFeatureIds[f.feature]},
                 {"value", number_or_null(f.value)},
                 {"significance", number_or_null(f.significance)},
                 {"rank", f.rank},
                 {"facet", facet_of(f.facet)},
                 {"concept", f.concept_ptr ? Json(f.concept_ptr->id) : Json(nullptr)},
                 {"agreement", number_or_null(f.agreement)},
                 {"stability", number_or_null(f.stability)},
                 {"chosen", f.chosen},
                 {"withheld", f.withheld}});
        t["features"] = features;
        if (!d.note.empty()) t["note"] = d.note;
        textures.push_back(t);
    }
    return textures;
}

Json words_json(const Annotation& a) {
    const Dictionary& dictionary = *a.dictionary;
    const DescriptionParams& params = a.options.description;
    Json j;
    j["dictionary"] = {{"id", dictionary.id},
                       {"version", dictionary.version},
                       {"source", dictionary.source_name},
                       {"sha256", dictionary.sha256}};
    j["choice"] = {{"max_concepts", params.max_concepts},
                   {"max_significance", params.max_significance},
                   {"min_agreement", params.min_agreement},
                   {"min_stability", params.min_stability},
                   {"resamples", params.num_resamples}};
    j["textures"] = texture_words_json(a, a.descriptions);
    return j;
}

// Per texel its orientation, texture, faces, seed, threshold and features.
Json texels_json(const Segmentation& seg) {
    Json texels = Json::array();
    for (std::size_t i = 0; i < seg.texels.size(); ++i) {
        const Texel& t = seg.texels[i];
        Json e;
        e["id"] = static_cast<int>(i);
        e["orientation"] = name_of(t.orientation);
        e["texture"] = seg.texel_texture[i];
        e["face_count"] = static_cast<int>(t.faces.size());
        e["seed_vertex"] = t.seed;
        e["depth_threshold"] = t.threshold;
        Json f;
        for (int k = 0; k < kNumFeatures; ++k)
            f[kFeatureIds[k]] = number_or_null(seg.features.values(static_cast<int>(i), k));
        e["features"] = f;
        e["faces"] = t.faces;
        texels.push_back(e);
    }
    return texels;
}

// Per texture its orientation, colour and texels.
Json textures_json(const Segmentation& seg) {
    Json textures = Json::array();
    for (int k = 0; k < seg.num_textures; ++k) {
        Json e;
        e["id"] = k;
        e["orientation"] = name_of(seg.texture_orientation[k]);
        e["colour"] = hex_colour(texture_colour(k));
        std::vector<int> members;
        for (std::size_t i = 0; i < seg.texels.size(); ++i)
            if (seg.texel_texture[i] == k) members.push_back(static_cast<int>(i));
        e["texel_count"] = static_cast<int>(members.size());
        e["texels"] = members;
        textures.push_back(e);
    }
    return textures;
}

// --levels: per level its scale, whether it is the main segmentation (the report's own texels),
// and for each of its texels the texel of the next coarser level it lies on (null: none); the
// other levels also list their texels and textures as the report does its own.
Json levels_json(const std::vector<DetailLevel>& levels, const Segmentation& main,
                 const Annotation* annotation) {
    Json out = Json::array();
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const DetailLevel& level = levels[k];
        const Segmentation& seg = level_segmentation(levels, k, main);
        Json e;
        e["level"] = static_cast<int>(k);
        e["scale"] = level.radius_rel;
        e["radius"] = seg.radius;
        e["main"] = level.main;
        e["texel_count"] = static_cast<int>(seg.texels.size());
        e["texture_count"] = seg.num_textures;
        Json part_of = Json::array();
        for (int c : level.part_of) part_of.push_back(c >= 0 ? Json(c) : Json(nullptr));
        e["part_of"] = part_of;
        if (!level.main) {
            e["texels"] = texels_json(seg);
            e["textures"] = textures_json(seg);
            if (annotation != nullptr)
                e["annotation"] =
                    texture_words_json(*annotation, annotation->level_descriptions[k]);
        }
        out.push_back(e);
    }
    return out;
}

Json segmentation_json(const Segmentation& seg, const SegmentationParams& params,
                       const ReportInput& input, const ScaleChoice* scale_choice) {
    Json j;
    j["geotex"] = {{"version", version()}, {"document", "segmentation"}, {"schema", 1}};
    j["input"] = input_json(input);
    j["parameters"] = parameters_json(params, seg.radius);
    if (scale_choice != nullptr) j["scale_choice"] = scale_choice_json(*scale_choice);
    // From the metrics, which every segmentation has: a tiled run's join holds no face arrays.
    j["mesh"] = {{"vertices", seg.metrics.num_vertices},
                 {"faces", seg.metrics.num_faces},
                 {"largest_side", seg.metrics.largest_side},
                 {"unit_scale", 1.0 / seg.metrics.largest_side},
                 {"mean_edge_length", seg.metrics.mean_edge_length}};
    j["smoothing"] = {{"disc_samples", seg.num_disc_samples},
                      {"interpolated_vertices", seg.num_interpolated_vertices}};
    Json depth = Json::array();
    for (std::size_t r = 0; r < seg.runs.size(); ++r) {
        const DepthMap& d =
            seg.runs[r] == DetailOrientation::Positive ? *seg.positive_depth : *seg.negative_depth;
        const TexelSet& set = seg.texel_sets[r];
        Json e;
        e["orientation"] = name_of(seg.runs[r]);
        e["max_depth"] = d.max_depth;
        e["moved_vertices"] = d.num_moved_vertices;
        e["global_threshold"] = number_or_null(set.global_threshold);
        e["seeds"] = set.num_local_maxima;
        e["regions"] = set.num_regions;
        e["merges"] = set.num_merges;
        e["excluded_opposite_texels"] =
            seg.run_excluded_texels.empty() ? 0 : seg.run_excluded_texels[r];
        e["textures"] = seg.clusterings[r].num_clusters;
        depth.push_back(e);
    }
    j["depth"] = depth;
    j["features"] = seg.features.names;

    j["texels"] = texels_json(seg);
    j["textures"] = textures_json(seg);
    Json diagnostics = Json::array();
    for (const auto& d : seg.diagnostics)
        diagnostics.push_back({{"stage", d.stage}, {"message", d.message}});
    j["diagnostics"] = diagnostics;
    return j;
}

}  // namespace

Json number_or_null(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

Json scale_choice_json(const ScaleChoice& choice) {
    // The series as `geotex scales --json` writes it, and which scale it gave.
    Json j = scale_series_json(choice.series, choice.params);
    j["chosen"] = choice.series.steps[choice.chosen].radius_rel;
    j["stable"] = choice.stable;
    return j;
}

Json segmentation_report(const Segmentation& segmentation, const SegmentationParams& params,
                         const ReportInput& input, const ScaleChoice* scale_choice,
                         const std::vector<DetailLevel>* levels) {
    check_sizes(segmentation, "segmentation_report");
    Json j = segmentation_json(segmentation, params, input, scale_choice);
    if (levels != nullptr && !levels->empty())
        j["levels"] = levels_json(*levels, segmentation, nullptr);
    return j;
}

Json annotation_report(const Annotation& annotation, const ReportInput& input) {
    if (!annotation.dictionary)
        throw InvalidInput(
            "annotation_report: the annotation has no dictionary; pass the result of "
            "annotate or annotate_segmentation as it is");
    check_sizes(annotation.segmentation, "annotation_report");
    const auto& choice = annotation.options.scale_choice;
    Json j = segmentation_json(annotation.segmentation, annotation.options.segmentation, input,
                               choice ? &*choice : nullptr);
    j["annotation"] = words_json(annotation);
    if (!annotation.levels.empty())
        j["levels"] = levels_json(annotation.levels, annotation.segmentation, &annotation);
    return j;
}

std::string report_text(const Json& report) { return report.dump(2) + '\n'; }

}  // namespace geotex
