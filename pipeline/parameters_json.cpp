#include "pipeline/parameters_json.hpp"

namespace geotex {

const char* orientation_name(OrientationMode mode) {
    switch (mode) {
        case OrientationMode::Positive:
            return "positive";
        case OrientationMode::Negative:
            return "negative";
        case OrientationMode::Both:
            return "both";
    }
    return "positive";
}

const char* orientation_name(DetailOrientation o) {
    return o == DetailOrientation::Positive ? "positive" : "negative";
}

const char* smoothing_name(SmoothingMethod m) {
    return m == SmoothingMethod::Mean ? "mean" : "twicing";
}

const char* disc_mode_name(DiscMode m) {
    switch (m) {
        case DiscMode::Exact:
            return "exact";
        case DiscMode::Fast:
            return "fast";
        case DiscMode::Auto:
            return "auto";
    }
    return "auto";
}

nlohmann::ordered_json parameters_json(const SegmentationParams& p, double radius) {
    nlohmann::ordered_json j;
    if (p.radius > 0)
        j["scale"] = nullptr;
    else
        j["scale"] = p.radius_rel;
    j["radius"] = radius;
    j["orientation"] = orientation_name(p.orientation);
    j["smoothing"] = smoothing_name(p.smoothing);
    j["area_weighted"] = p.area_weighted;
    j["disc"] = disc_mode_name(p.disc);
    j["curvature_scale"] = p.curvature_scale;
    j["merge_overlap"] = p.merge_overlap;
    j["min_depth_rel"] = p.min_depth_rel;
    j["min_faces"] = p.min_faces;
    j["remove_rims"] = p.remove_rims;
    j["neighbour_rank"] = p.clustering.neighbour_rank;
    j["max_textures"] = p.clustering.max_clusters;
    return j;
}

}  // namespace geotex
