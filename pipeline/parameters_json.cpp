#include "pipeline/parameters_json.hpp"

namespace geotex {

nlohmann::ordered_json parameters_json(const SegmentationParams& p, double radius) {
    nlohmann::ordered_json j;
    if (p.radius > 0)
        j["scale"] = nullptr;
    else
        j["scale"] = p.radius_rel;
    j["radius"] = radius;
    j["orientation"] = name_of(p.orientation);
    j["smoothing"] = name_of(p.smoothing);
    j["area_weighted"] = p.area_weighted;
    j["disc"] = name_of(p.disc);
    j["curvature_scale"] = p.curvature_scale;
    j["merge_overlap"] = p.merge_overlap;
    j["min_depth_rel"] = p.min_depth_rel;
    j["min_faces"] = p.min_faces;
    j["remove_rims"] = p.remove_rims;
    j["neighbour_rank"] = p.clustering.neighbour_rank;
    j["max_textures"] = p.clustering.max_clusters;
    j["cluster_landmarks"] = p.clustering.max_points;
    return j;
}

}  // namespace geotex
