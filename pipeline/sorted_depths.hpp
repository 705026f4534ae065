#pragma once
// A depth part's depths sorted, in a file beside the part (DIR/depth/tile-K.sorted,
// docs/tiles.md): the seeds' threshold of a texel pass is Otsu's over every vertex depth of the
// mesh, which reads them in ascending order, and a texel job merges these files a block of
// each at a time (otsu_threshold_merged) instead of holding the whole mesh's depths. The
// header carries the run's key, the pass, the tile, each orientation's count and greatest
// depth (which the features jobs need of every tile) and the part's counts of moved,
// interpolated and sampled vertices (which, with the greatest depths, are all the join of the
// outputs takes of a depth part); then each orientation's depths as little-endian doubles,
// ascending, -0.0 written as 0.0.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "geometry/otsu.hpp"
#include "geometry/tiled_segmentation.hpp"

namespace geotex {

/// Writes depth part `part`'s depths sorted, with the run's key. Throws InvalidInput when the
/// part is not of a depth pass or a depth is not finite.
void write_sorted_depths(std::ostream& out, const std::string& key, const TilePart& part);

/// One tile's sorted depths file: its header read and checked when opened, its depths read a
/// block at a time by each orientation's SortedValues.
class SortedDepthsFile {
  public:
    /// Opens `path` and checks that it is the run `key`'s file of pass `pass` and tile `tile`
    /// (0-based), whole. Throws IoError when it cannot be opened, InvalidInput (naming the
    /// file) when it is another run's, pass's or tile's, or damaged.
    SortedDepthsFile(std::string path, const std::string& key, TilePass pass, int tile);

    /// Orientations of the pass (as in the part).
    std::size_t orientations() const { return counts_.size(); }
    /// Orientation i's depths, ascending, read from the file as the merge asks for them.
    std::unique_ptr<SortedValues> values(std::size_t i) const;
    /// Each orientation's greatest depth, 0 when it has none.
    const std::vector<double>& greatest() const { return greatest_; }
    /// What the join of the outputs takes of the part (TiledSegmentation::add_depth_summary);
    /// none in a file made before it was kept there.
    const std::optional<DepthPartSummary>& summary() const { return summary_; }

  private:
    std::string path_;
    std::vector<std::uint64_t> counts_;   // per orientation
    std::vector<std::uint64_t> offsets_;  // per orientation: the first depth's byte in the file
    std::vector<double> greatest_;        // per orientation
    std::optional<DepthPartSummary> summary_;
};

/// The seeds' thresholds of a texel pass (one per orientation of its depth pass), which every
/// texel job of the pass would otherwise merge the same sorted depths for: the first job
/// leaves them in DIR/<texel pass>/seed-thresholds for the others. Writes them with the run's
/// key.
void write_seed_thresholds(std::ostream& out, const std::string& key, TilePass texel_pass,
                           const std::vector<double>& thresholds);

/// The thresholds `in` holds, checked to be the run `key`'s, of pass `texel_pass` and
/// `orientations` of them, each finite and not negative. Throws InvalidInput saying what is
/// wrong.
std::vector<double> read_seed_thresholds(std::istream& in, const std::string& key,
                                         TilePass texel_pass, std::size_t orientations);

}  // namespace geotex
