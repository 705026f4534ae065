#pragma once
/// The segmentation parameters as JSON, in one fixed key order: the "parameters" of the JSON
/// report, and the canonical text that the keys of geometry caches and batch stamps hash.

#include <nlohmann/json.hpp>

#include "geometry/segmentation.hpp"

namespace geotex {

/// The parameters as used, `radius` the radius resolved in mesh units (0: not yet resolved,
/// as in the keys of caches): scale (null when a radius was given), radius, orientation,
/// smoothing, area_weighted, disc, curvature_scale, merge_overlap, min_depth_rel, min_faces,
/// remove_rims, neighbour_rank, max_textures.
nlohmann::ordered_json parameters_json(const SegmentationParams& params, double radius);

}  // namespace geotex
