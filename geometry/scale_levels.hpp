#pragma once
/// Several scales at once (issue 20; docs/scales.md, "Several levels"): the recommended scale
/// of every plateau of the series is a level of detail, segmented on its own, and each texel
/// of a level is linked to the texel of the next coarser level that it lies on. The paper's
/// two-level experiment (§4.1, Fig. 15: strokes on bumps) in one run: the strokes at the fine
/// level, the bumps at the coarse one, and which stroke lies on which bump.

#include <vector>

#include "geometry/mesh.hpp"
#include "geometry/scale_series.hpp"
#include "geometry/segmentation.hpp"

namespace geotex {

/// A fine texel lies on a coarse one when more than this fraction of its faces are the coarse
/// texel's (the overlap coefficient |fine ∩ coarse| / |fine|). Above one half, a fine texel
/// lies on one coarse texel at most.
inline constexpr double kPartOfCover = 0.5;

/// One level: its scale and, but for the main level, its own segmentation.
struct DetailLevel {
    int step = -1;          ///< index into the series' steps
    double radius_rel = 0;  ///< r, fraction of the largest side
    bool main = false;      ///< the chosen scale, whose segmentation the caller holds
    /// This level's texels and textures; empty for the main level (its segmentation is the
    /// caller's, e.g. Annotation::segmentation).
    Segmentation segmentation;
    /// #texels of this level: the texel of the next coarser level that holds more than
    /// kPartOfCover of its faces, or -1 (none, and always at the coarsest level).
    std::vector<int> part_of;
};

/// The series' steps that become levels, fine to coarse: the recommended step of every
/// plateau, and the chosen step when it is none of them (no stable scale: then it is alone).
std::vector<int> level_steps(const ScaleChoice& choice);

/// For two labellings of the same faces (#F each, texel id or -1; `fine_count` texels in
/// `fine`), the texel of `coarse` that holds more than `min_cover` (>= 0.5) of each fine
/// texel's faces, or -1. Returns #fine_count ids.
std::vector<int> covering_texels(const std::vector<int>& fine_face_texel, int fine_count,
                                 const std::vector<int>& coarse_face_texel,
                                 double min_cover = kPartOfCover);

/// The levels of `choice` (level_steps), fine to coarse: each one but the chosen scale is
/// segmented with `base` at its scale (`observer` is told before each), the chosen one is
/// `main` (run_segmentation at that scale, which the caller has), and every level's part_of
/// is filled. Deterministic for any thread count. Throws as run_segmentation.
std::vector<DetailLevel> segment_levels(const Mesh& mesh, const SegmentationParams& base,
                                        const ScaleChoice& choice, const Segmentation& main,
                                        const ScaleObserver& observer = {});

/// The face labelling of level `k`: its own, or `main`'s for the main level.
inline const Segmentation& level_segmentation(const std::vector<DetailLevel>& levels, std::size_t k,
                                              const Segmentation& main) {
    return levels[k].main ? main : levels[k].segmentation;
}

}  // namespace geotex
