#pragma once
// The steps of run_segmentation (segmentation.cpp) that do not need the mesh's topology,
// shared with the tiled pipeline (tiles.cpp), which makes the depth maps and texels otherwise.

#include <optional>
#include <utility>
#include <vector>

#include "geometry/segmentation.hpp"

namespace geotex::detail {

/// The diagnostic of a radius below three mean edge lengths (the discs hold too few vertices),
/// or nothing. Both lengths in the same unit.
std::optional<Diagnostic> radius_diagnostic(double radius, double mean_edge_length);

/// One orientation's final depth map and texels.
struct OrientationResult {
    DetailOrientation orientation = DetailOrientation::Positive;
    DepthMap depth;
    TexelSet texels;
};

/// Moves the texels of every run (in `runs`' order, positive first) into seg.texels; a face
/// already in a texel of an earlier run stays there, and a texel left with fewer than
/// `min_faces` faces is dropped. Fills seg.face_texel (#F = num_faces), seg.texel_sets,
/// seg.positive_depth / negative_depth and the texel sets' diagnostics. Returns each run's
/// [first, last) texel ids.
std::vector<std::pair<int, int>> collect_texels(Segmentation& seg, int num_faces, int min_faces,
                                                std::vector<OrientationResult> runs);

/// The textures (paper §3.4): each run's texels (ranges from collect_texels) clustered on their
/// own from seg.features, so that a texture never mixes orientations.
void cluster_textures(Segmentation& seg, int num_faces,
                      const std::vector<std::pair<int, int>>& run_texel_range,
                      const ClusteringParams& params);

}  // namespace geotex::detail
