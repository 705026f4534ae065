#include "geometry/scale_levels.hpp"

#include <algorithm>

#include "common/errors.hpp"

namespace geotex {

std::vector<int> level_steps(const ScaleChoice& choice) {
    std::vector<int> steps;
    for (const ScalePlateau& p : choice.series.plateaus) steps.push_back(p.recommended);
    if (std::find(steps.begin(), steps.end(), choice.chosen) == steps.end())
        steps.push_back(choice.chosen);
    // Plateaus come fine to coarse already; the fallback (no plateau) is alone.
    std::sort(steps.begin(), steps.end());
    return steps;
}

std::vector<int> covering_texels(const std::vector<int>& fine_face_texel, int fine_count,
                                 const std::vector<int>& coarse_face_texel, double min_cover) {
    if (!(min_cover >= 0.5 && min_cover < 1))
        throw InvalidInput("covering_texels: the cover must be in [0.5, 1)");
    const int coarse_count =
        coarse_face_texel.empty()
            ? 0
            : 1 + *std::max_element(coarse_face_texel.begin(), coarse_face_texel.end());
    const TexelOverlaps o =
        texel_overlaps(fine_face_texel, fine_count, coarse_face_texel, coarse_count);
    std::vector<int> cover(static_cast<std::size_t>(fine_count), -1);
    // Above one half, one coarse texel at most passes: the pairs' order does not matter.
    for (const TexelOverlaps::Pair& p : o.pairs)
        if (static_cast<double>(p.shared) > min_cover * static_cast<double>(o.size_a[p.a]))
            cover[static_cast<std::size_t>(p.a)] = p.b;
    return cover;
}

std::vector<DetailLevel> segment_levels(const Mesh& mesh, const SegmentationParams& base,
                                        const ScaleChoice& choice, const Segmentation& main,
                                        const ScaleObserver& observer) {
    const std::vector<int> steps = level_steps(choice);
    std::vector<DetailLevel> levels(steps.size());
    for (std::size_t k = 0; k < steps.size(); ++k) {
        DetailLevel& level = levels[k];
        level.step = steps[k];
        level.radius_rel = choice.series.steps[static_cast<std::size_t>(steps[k])].radius_rel;
        level.main = steps[k] == choice.chosen;
        if (level.main) continue;
        if (observer)
            observer(static_cast<int>(k), static_cast<int>(steps.size()), level.radius_rel);
        SegmentationParams p = base;
        p.radius_rel = level.radius_rel;
        p.radius = 0;
        level.segmentation = run_segmentation(mesh, p);
        // The depth maps and the topology are the bulk of a segmentation and no output of a
        // level uses them (its texels, features and textures are what is written).
        level.segmentation.topology = MeshTopology{};
        level.segmentation.positive_depth.reset();
        level.segmentation.negative_depth.reset();
    }
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const Segmentation& fine = level_segmentation(levels, k, main);
        const int count = static_cast<int>(fine.texels.size());
        levels[k].part_of =
            k + 1 < levels.size()
                ? covering_texels(fine.face_texel, count,
                                  level_segmentation(levels, k + 1, main).face_texel)
                : std::vector<int>(static_cast<std::size_t>(count), -1);
    }
    return levels;
}

}  // namespace geotex
