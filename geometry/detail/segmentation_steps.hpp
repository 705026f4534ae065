#pragma once
// The steps of run_segmentation (segmentation.cpp) that do not need the mesh's topology,
// shared with the tiled pipeline (tiles.cpp, tile_texels.cpp), which makes the depth maps and
// texels otherwise.

#include <chrono>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "geometry/rims.hpp"
#include "geometry/segmentation.hpp"

namespace geotex::detail {

/// Runs fn as a stage: tells the observer before (seconds < 0) and after (its wall time), and
/// returns what fn returns.
template <class Fn>
auto timed(const StageObserver& observer, const std::string& stage, Fn&& fn) {
    if (observer) observer({stage, -1.0});
    const auto start = std::chrono::steady_clock::now();
    auto finish = [&] {
        if (observer)
            observer(
                {stage,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    };
    if constexpr (std::is_void_v<decltype(fn())>) {
        fn();
        finish();
    } else {
        auto result = fn();
        finish();
        return result;
    }
}

/// The orientations a mode asks for, positive first.
std::vector<DetailOrientation> orientations_of(OrientationMode mode);

/// The smoothing, texel and rim parameters of a run at radius `radius` (mesh units).
SmoothingParams smoothing_params(const SegmentationParams& params, double radius);
TexelParams texel_params(const SegmentationParams& params, double radius);
RimParams rim_params(double radius);

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
/// `min_faces` faces is dropped. Fills seg.texel_sets, seg.positive_depth / negative_depth,
/// the texel sets' diagnostics and, with `face_labels`, seg.face_texel (#F = num_faces; the join
/// of a tiled run leaves it out, 4 bytes a face, and labels the faces as it writes them).
/// Returns each run's [first, last) texel ids.
std::vector<std::pair<int, int>> collect_texels(Segmentation& seg, int num_faces, int min_faces,
                                                std::vector<OrientationResult> runs,
                                                bool face_labels = true);

/// The textures (paper §3.4): each run's texels (ranges from collect_texels) clustered on their
/// own from seg.features, so that a texture never mixes orientations. Fills seg.face_texture
/// when collect_texels made seg.face_texel.
void cluster_textures(Segmentation& seg, int num_faces,
                      const std::vector<std::pair<int, int>>& run_texel_range,
                      const ClusteringParams& params);

}  // namespace geotex::detail
