#pragma once
/// The texels of one mesh over a geometric series of scales, and the scales where they are
/// stable (issue 20; the rule and its reasoning: docs/scales.md). The paper leaves the scale
/// r to the user; on its sphere any r from 1.5% to 6% works, on an inscription not.
///
/// A texel found at one scale *persists* into a neighbouring scale when a texel there covers
/// nearly the same faces (intersection over union above `match_iou`): a real detail keeps its
/// texel over a range of r, while a texel raised by noise or wear at a small r, or one that
/// merges details at a large r, does not. A scale is *stable* when most of its texels persist
/// into its neighbouring scales (docs/scales.md: how they are counted); runs of two or more
/// stable scales are the plateaus, and a plateau recommends, of its scales with nearly its
/// most persistent texels, the one with the fewest texels that do not persist.

#include <functional>
#include <string>
#include <vector>

#include "geometry/mesh.hpp"
#include "geometry/segmentation.hpp"

namespace geotex {

struct ScaleSeriesParams {
    double min_rel = 0.01;  ///< smallest r, fraction of the largest bounding-box side
    double max_rel = 0.16;  ///< largest r (the series is geometric from min_rel to max_rel)
    int steps = 12;         ///< number of scales, >= 2
    /// Two texels of neighbouring scales are one detail when the intersection of their face
    /// sets exceeds this fraction of their union. Above 0.5 a texel has at most one partner.
    double match_iou = 0.5;
    /// A scale is stable when at least this fraction of its texels persist into both of its
    /// neighbouring scales (into the one it has, at either end of the series).
    double stable_fraction = 0.8;
    /// Scales whose r is below this many mean edge lengths are skipped: a disc of a few
    /// vertices gives no depth to speak of, only the sampling's noise.
    double min_radius_edges = 3;
    /// A plateau recommends, of its scales whose persistent texels are at least this
    /// fraction of the plateau's most, the one with the fewest texels that do not persist
    /// (the finest on a tie).
    double near_most = 0.95;
};

/// One scale of the series.
struct ScaleStep {
    double radius_rel = 0;  ///< r, fraction of the largest side
    double radius = 0;      ///< r, mesh units
    bool skipped = false;   ///< below min_radius_edges: not segmented
    int texels = 0;
    int textures = 0;
    int persist_previous = 0;  ///< texels matched in the previous computed scale
    int persist_next = 0;      ///< texels matched in the next computed scale
    /// The smaller of persist_previous and persist_next (the only one at an end): at most
    /// the texels matched both ways, equal when one side's matches are the other's.
    int persistent = 0;
    double stability = 0;      ///< persistent / texels; 0 without texels
    bool stable = false;       ///< stability >= stable_fraction and at least one texel
};

/// A run of at least two consecutive stable scales (indices into ScaleSeries::steps, skipped
/// ones never inside) and its recommended scale. One stable scale alone is not a plateau: at
/// an end of the series it was compared with a single neighbour, and within it, its
/// neighbours did not keep its texels themselves.
struct ScalePlateau {
    int first = 0;
    int last = 0;
    int recommended = 0;  ///< of the steps with nearly the most persistent texels
                          ///< (ScaleSeriesParams::near_most), the one with the fewest
                          ///< texels that do not persist, the finest on a tie
};

struct ScaleSeries {
    std::vector<ScaleStep> steps;
    std::vector<ScalePlateau> plateaus;
    int best = -1;  ///< the recommended step of the plateau with the most persistent texels
                    ///< (the finer plateau on a tie); -1: none stable
    std::vector<std::string> notes;  ///< e.g. scales skipped, and why
};

/// A scale as the tables and messages write it: "2.74%" (three significant digits).
std::string scale_percent(double radius_rel);

/// The scales of the series: min_rel * (max_rel / min_rel)^(k / (steps - 1)), k = 0..steps-1.
/// Throws InvalidInput unless 0 < min_rel < max_rel < 1 and steps >= 2.
std::vector<double> scale_series_radii(const ScaleSeriesParams& params);

/// How two labellings of the same faces (#F each, texel id or -1; `na` and `nb` texels)
/// overlap: each texel's face count and, for every pair of texels that meet, the faces they
/// share. What persisting_texels and covering_texels (scale_levels.hpp) both measure. Throws
/// InvalidInput when the labellings differ in size or an id is not below its count.
struct TexelOverlaps {
    std::vector<long> size_a;  ///< #na
    std::vector<long> size_b;  ///< #nb
    struct Pair {
        int a = 0;
        int b = 0;
        long shared = 0;
    };
    std::vector<Pair> pairs;  ///< in no particular order
};
TexelOverlaps texel_overlaps(const std::vector<int>& face_texel_a, int na,
                             const std::vector<int>& face_texel_b, int nb);

/// For two labellings of the same faces (#F each, texel id or -1), which texels of `a` have a
/// partner in `b` with intersection over union above `min_iou` (min_iou >= 0.5: one partner
/// at most). Returns #texels_a flags; na and nb are the texel counts.
std::vector<bool> persisting_texels(const std::vector<int>& face_texel_a, int na,
                                    const std::vector<int>& face_texel_b, int nb, double min_iou);

/// Fills persistent, stability and stable of every computed step from persist_previous and
/// persist_next, then the plateaus and the best step. Exposed for tests of the rule alone.
void choose_scales(ScaleSeries& series, const ScaleSeriesParams& params);

/// The scale `--scale auto` takes from a series, and the series it came from (reports and RDF
/// record both, so that a reader knows the scale was chosen and how).
struct ScaleChoice {
    ScaleSeriesParams params;
    ScaleSeries series;
    int chosen = -1;      ///< index into series.steps
    bool stable = false;  ///< the best scale of a plateau; false: no stable scale, the fallback
};

/// The best scale of the series, or, when there is no stable scale, the computed scale with
/// the most persistent texels (the finest on a tie; on a mesh without detail, the finest
/// computed scale, which finds no texel as every other). Throws InvalidInput when every scale
/// was skipped.
ScaleChoice choose_scale(ScaleSeries series, const ScaleSeriesParams& params);

/// Called before each scale is segmented: its index, the number of scales, its r (relative).
using ScaleObserver = std::function<void(int index, int count, double radius_rel)>;

/// Segments `mesh` at every scale of the series with `base` (its radius_rel and radius are
/// replaced) and chooses the stable scales. Deterministic for any thread count. Throws
/// InvalidInput on bad parameters.
ScaleSeries run_scale_series(const Mesh& mesh, const SegmentationParams& base,
                             const ScaleSeriesParams& params = {},
                             const ScaleObserver& observer = {});

}  // namespace geotex
