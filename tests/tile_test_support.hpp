#pragma once
// What the tests of a tiled run's jobs share (test_tile_mesh.cpp: the tile meshes on disk;
// test_tile_alone.cpp: the parts made from a tile alone; test_sorted_depths.cpp: the sorted
// depths and thresholds beside the parts): the parameters they run with and the first depth
// pass made by the whole run.

#include <cstddef>
#include <vector>

#include "geometry/segmentation.hpp"
#include "geometry/tiled_segmentation.hpp"
#include "tests/fixtures.hpp"

namespace geotex::tile_test {

/// The fast disc mode, so that the sampling's flags and grid matter.
inline SegmentationParams fast_params() {
    SegmentationParams p;
    p.radius_rel = 0.04;
    p.disc = DiscMode::Fast;
    return p;
}

/// Every tile's part of the first depth pass, joined into `run`, which then waits for the
/// texels.
inline std::vector<TilePart> depth_parts(TiledSegmentation& run) {
    std::vector<TilePart> parts;
    for (int b = 0; b < run.num_tiles(); ++b) parts.push_back(run.run_tile(b));
    for (const TilePart& part : parts) run.add(part);
    run.finish_pass();
    return parts;
}

/// Whether two depth parts give the same depths, bit for bit, and the same moved counts.
inline bool same_depths(const TilePart& a, const TilePart& b) {
    if (a.depths.size() != b.depths.size() || a.moved != b.moved) return false;
    for (std::size_t i = 0; i < a.depths.size(); ++i) {
        if (a.depths[i].size() != b.depths[i].size()) return false;
        for (std::size_t k = 0; k < a.depths[i].size(); ++k)
            if (!test::same_bits(a.depths[i][k], b.depths[i][k])) return false;
    }
    return true;
}

}  // namespace geotex::tile_test
