#include "cli/report.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>

#include "common/errors.hpp"
#include "pipeline/report_json.hpp"

namespace geotex::cli {

Json ground_truth_json(const std::string& mesh_file, const SynthParams& p,
                       const SyntheticMesh& synth) {
    Json j;
    j["geotex"] = {{"version", GEOTEX_VERSION}, {"document", "ground_truth"}, {"schema", 1}};
    j["mesh"] = {{"file", mesh_file},
                 {"vertices", synth.mesh.num_vertices()},
                 {"faces", synth.mesh.num_faces()}};
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
            throw ParseError("not a geotex ground truth (needs \"shapes\" and \"face_shape\")",
                             file);
        GroundTruth gt;
        std::map<std::string, int> kinds, families;
        for (const auto& s : j.at("shapes")) {
            const std::string kind = s.at("kind").get<std::string>();
            const std::string family =
                s.contains("family") ? s.at("family").get<std::string>() : kind;
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

void write_json(std::ostream& out, const Json& json) { out << report_text(json); }

}  // namespace geotex::cli
