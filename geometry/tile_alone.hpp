#pragma once
/// A tile's parts of the first depth and texel passes of a tiled run made from the tile alone
/// (docs/tiles.md, "Tiles as separate jobs"): the DepthTile that the run's mesh job writes
/// (TiledSegmentation::depth_tile, pipeline/tile_mesh.hpp) and the parts of the depth pass,
/// read one at a time, give the parts that TiledSegmentation::run_tile gives, bit for bit,
/// without the whole mesh.

#include <functional>
#include <optional>
#include <vector>

#include "geometry/tiled_segmentation.hpp"

namespace geotex {

/// A tile's part of the first depth pass (TilePass::Depth) made from its DepthTile alone: the
/// part TiledSegmentation::run_tile gives that tile in that pass, bit for bit, with the same
/// `params`. The tile is cut to the depth halo first (taken by value, so that a caller that
/// moves it in does not hold both). Throws InvalidInput when `params` are not valid, the
/// tile's halo is narrower than the depth halo, or its arrays do not fit its vertices.
TilePart first_depth_part(DepthTile tile, const SegmentationParams& params);

/// Tile k's part of a pass (k in [0, num_tiles)), for a job that reads the parts of the pass
/// before its own one at a time instead of joining them.
using TilePartSource = std::function<TilePart(int)>;

/// The seeds' thresholds of the first texel pass, one per orientation of the first depth pass,
/// from every tile's part of that pass (part_of), with the run's numbers that any of its tiles
/// carries: what TiledSegmentation computes from the joined depth maps, bit for bit. Holds one
/// orientation's depths of every vertex at a time (8 bytes a vertex), not the mesh; reads each
/// part once per orientation. Throws InvalidInput when a part is not its tile's part of the
/// first depth pass or its sizes do not fit.
std::vector<double> first_texel_thresholds(const DepthTile& tile, const SegmentationParams& params,
                                           const TilePartSource& part_of);

/// The first depth pass's depths at the tile's vertices, one array of #V_tile per orientation
/// of that pass, picked from every tile's part (part_of). Throws InvalidInput as
/// first_texel_thresholds, and when the parts do not give every vertex of the tile its depth.
std::vector<std::vector<double>> first_depths_in_tile(const DepthTile& tile,
                                                      const SegmentationParams& params,
                                                      const TilePartSource& part_of);

/// A tile's part of the first texel pass (TilePass::Texels) from its DepthTile, its vertices'
/// depths (first_depths_in_tile) and the thresholds (first_texel_thresholds): the part
/// TiledSegmentation::run_tile gives, bit for bit. std::nullopt when a region grows past what
/// the tile's halo holds (with kTileMeshHaloRadii, the texel halo 3r widened twice, to 12r):
/// the part then needs the whole mesh. Throws InvalidInput as first_depth_part, and when the
/// depths or thresholds do not fit.
std::optional<TilePart> first_texel_part(const DepthTile& tile,
                                         const std::vector<std::vector<double>>& depths,
                                         const std::vector<double>& thresholds,
                                         const SegmentationParams& params);

}  // namespace geotex
