#include "cli/report.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>

#include "annotation/texture_label.hpp"
#include "cli/output.hpp"
#include "common/errors.hpp"

namespace geotex::cli {

namespace {

Json number_or_null(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

}  // namespace

Json input_json(const std::string& file, const std::string& format, const MeshRepairReport& r) {
    Json j;
    j["file"] = file;
    j["format"] = format;
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

Json segmentation_json(const Json& input, const SegmentationParams& params, const Segmentation& seg) {
    Json j;
    j["geotex"] = {{"version", GEOTEX_VERSION}, {"document", "segmentation"}, {"schema", 1}};
    j["input"] = input;
    j["parameters"] = parameters_json(params, seg.radius);
    const int nv = static_cast<int>(seg.metrics.vertex_area.size());
    j["mesh"] = {{"vertices", nv},
                 {"faces", static_cast<int>(seg.face_texel.size())},
                 {"largest_side", seg.metrics.largest_side},
                 {"unit_scale", 1.0 / seg.metrics.largest_side},
                 {"mean_edge_length", seg.metrics.mean_edge_length}};
    j["smoothing"] = {{"disc_samples", seg.num_disc_samples},
                      {"interpolated_vertices", seg.num_interpolated_vertices}};
    Json depth = Json::array();
    for (std::size_t r = 0; r < seg.runs.size(); ++r) {
        const DepthMap& d = seg.runs[r] == DetailOrientation::Positive ? *seg.positive_depth : *seg.negative_depth;
        const TexelSet& set = seg.texel_sets[r];
        Json e;
        e["orientation"] = name_of(seg.runs[r]);
        e["max_depth"] = d.max_depth;
        e["moved_vertices"] = d.num_moved_vertices;
        e["global_threshold"] = number_or_null(set.global_threshold);
        e["seeds"] = set.num_local_maxima;
        e["regions"] = set.num_regions;
        e["merges"] = set.num_merges;
        e["excluded_opposite_texels"] = seg.run_excluded_texels.empty() ? 0 : seg.run_excluded_texels[r];
        e["textures"] = seg.clusterings[r].num_clusters;
        depth.push_back(e);
    }
    j["depth"] = depth;
    j["features"] = seg.features.names;

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
        for (int k = 0; k < kNumFeatures; ++k) f[kFeatureIds[k]] = number_or_null(seg.features.values(static_cast<int>(i), k));
        e["features"] = f;
        e["faces"] = t.faces;
        texels.push_back(e);
    }
    j["texels"] = texels;
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
    j["textures"] = textures;
    Json diagnostics = Json::array();
    for (const auto& d : seg.diagnostics) diagnostics.push_back({{"stage", d.stage}, {"message", d.message}});
    j["diagnostics"] = diagnostics;
    return j;
}

Json annotation_json(const Dictionary& dictionary, const std::vector<TextureDescription>& descriptions,
                     const DescriptionParams& params, const std::string& lang) {
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
        for (int i : d.chosen) chosen.push_back(concept_entry(d.features[static_cast<std::size_t>(i)]));
        t["concepts"] = chosen;
        Json withheld = Json::array();
        for (int i : d.withheld) withheld.push_back(concept_entry(d.features[static_cast<std::size_t>(i)]));
        t["withheld"] = withheld;
        Json features = Json::array();
        for (const auto& f : d.features)
            features.push_back({{"feature", kFeatureIds[f.feature]},
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
    j["textures"] = textures;
    return j;
}

Json ground_truth_json(const std::string& mesh_file, const SynthParams& p, const SyntheticMesh& synth) {
    Json j;
    j["geotex"] = {{"version", GEOTEX_VERSION}, {"document", "ground_truth"}, {"schema", 1}};
    j["mesh"] = {{"file", mesh_file}, {"vertices", synth.mesh.num_vertices()}, {"faces", synth.mesh.num_faces()}};
    j["parameters"] = {{"level", p.level},
                       {"big_discs", p.num_big_discs},
                       {"small_discs", p.num_small_discs},
                       {"squares", p.num_squares},
                       {"rectangles", p.num_rectangles},
                       {"displacement_rel", p.displacement_rel},
                       {"edge_width_rel", p.edge_width_rel},
                       {"gap_rel", p.gap_rel},
                       {"noise_percent", p.noise_percent},
                       {"engraved_fraction", p.engraved_fraction},
                       {"layout_seed", p.layout_seed},
                       {"noise_seed", p.noise_seed}};
    Json shapes = Json::array();
    for (const auto& s : synth.shapes) {
        Json e;
        e["id"] = s.id;
        e["kind"] = shape_kind_name(s.kind);
        e["family"] = shape_kind_family(s.kind);
        e["engraved"] = s.engraved;
        e["center"] = {s.center.x(), s.center.y(), s.center.z()};
        e["angle"] = s.angle;
        e["half_length"] = s.half_length;
        e["half_width"] = s.half_width;
        shapes.push_back(e);
    }
    j["shapes"] = shapes;
    j["face_shape"] = synth.face_shape;
    return j;
}

GroundTruth read_ground_truth(const std::string& file, std::vector<std::string>* kind_names) {
    // A directory opens as a stream whose first read throws a bare std::ios_base::failure.
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        throw IoError("cannot read the ground truth: it is a directory", file);
    std::ifstream in(file, std::ios::binary);
    if (!in) throw IoError("cannot open the ground truth", file);
    Json j;
    try {
        j = Json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
        throw ParseError(std::string("not valid JSON: ") + e.what(), file);
    }
    try {
        if (!j.contains("shapes") || !j.contains("face_shape"))
            throw ParseError("not a geotex ground truth (needs \"shapes\" and \"face_shape\")", file);
        GroundTruth gt;
        std::map<std::string, int> kinds, families;
        for (const auto& s : j.at("shapes")) {
            const std::string kind = s.at("kind").get<std::string>();
            const std::string family = s.contains("family") ? s.at("family").get<std::string>() : kind;
            kinds.emplace(kind, static_cast<int>(kinds.size()));
            families.emplace(family, static_cast<int>(families.size()));
            gt.shape_kind.push_back(kinds.at(kind));
            gt.shape_family.push_back(families.at(family));
            if (s.at("id").get<int>() != static_cast<int>(gt.shape_kind.size()) - 1)
                throw ParseError("shape ids must be 0, 1, 2, ... in order", file);
        }
        gt.face_shape = j.at("face_shape").get<std::vector<int>>();
        if (kind_names) {
            kind_names->assign(kinds.size(), "");
            for (const auto& [name, id] : kinds) (*kind_names)[id] = name;
        }
        return gt;
    } catch (const nlohmann::json::exception& e) {
        throw ParseError(std::string("malformed ground truth: ") + e.what(), file);
    }
}

Json score_json(const SegmentationScore& s) {
    Json j;
    j["hausdorff"] = number_or_null(s.hausdorff);
    j["hausdorff_matched"] = number_or_null(s.hausdorff_matched);
    j["delta_t"] = s.delta_t;
    j["hausdorff_over_delta_t"] = number_or_null(s.delta_t > 0 ? s.hausdorff / s.delta_t : NAN);
    j["shapes"] = s.num_shapes;
    j["texels"] = s.num_texels;
    j["matched"] = s.num_matched;
    j["missed"] = s.num_missed;
    j["split"] = s.num_split;
    j["spurious"] = s.num_spurious;
    j["ari_kind"] = s.ari_kind;
    j["ari_family"] = s.ari_family;
    return j;
}

void write_json(std::ostream& out, const Json& json) { out << json.dump(2) << '\n'; }

}  // namespace geotex::cli
