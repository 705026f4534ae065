#pragma once
/// A tile's parts of the passes of a tiled run made from the tile alone (docs/tiles.md, "Tiles
/// as separate jobs"): the DepthTile that the run's mesh job writes
/// (TiledSegmentation::depth_tile, pipeline/tile_mesh.hpp) and the parts of the passes before,
/// read one at a time, give the parts that TiledSegmentation::run_tile gives, bit for bit,
/// without the whole mesh.

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/otsu.hpp"
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

/// A depth pass of a tiled run and its orientations, whose parts a texel pass reads: the first
/// (first_depth_pass) or the second smoothing's (JoinedRims::second).
struct DepthPassOf {
    TilePass pass = TilePass::Depth;  ///< Depth or DepthWithoutRims
    std::vector<DetailOrientation> orientations;
};
/// The first depth pass: both orientations when rims are removed, else those asked for.
DepthPassOf first_depth_pass(const SegmentationParams& params);
/// The texel pass that reads depth pass `depth_pass`: Texels after Depth, TexelsWithoutRims
/// after DepthWithoutRims.
TilePass texel_pass_after(TilePass depth_pass);

/// Depth pass `of`'s depths at the tile's vertices, one array of #V_tile per orientation of
/// that pass, picked from the parts (part_of) of the tiles whose boxes hold a vertex of the
/// tile; the other parts are not read. Throws InvalidInput when a part read is not its tile's
/// part of that depth pass or its sizes do not fit, and when the parts do not give every
/// vertex of the tile its depth.
std::vector<std::vector<double>> depths_in_tile(const DepthTile& tile,
                                                const SegmentationParams& params,
                                                const DepthPassOf& of,
                                                const TilePartSource& part_of);

/// Tile k's depths of a depth pass sorted, orientation i of the pass (k in [0, num_tiles)):
/// what texel_thresholds_merged merges, read a block at a time from a file beside the part.
using SortedDepthSource =
    std::function<std::unique_ptr<SortedValues>(int tile, std::size_t orientation)>;

/// The seeds' thresholds of the texel pass after depth pass `of`, one per orientation of that
/// pass, from every tile's depths sorted (sorted_of), with the run's numbers that any of its
/// tiles carries: what TiledSegmentation computes from the joined depth maps, bit for bit,
/// holding a block of each tile's depths instead of every vertex's (otsu_threshold_merged).
/// Throws InvalidInput when the tiles give more depths than the mesh has vertices, or a tile's
/// sorted depths are damaged.
std::vector<double> texel_thresholds_merged(const DepthTile& tile, const SegmentationParams& params,
                                            const DepthPassOf& of,
                                            const SortedDepthSource& sorted_of);

/// A tile's part of the texel pass after depth pass `of` (TilePass::Texels after the first,
/// TexelsWithoutRims after the second smoothing) from its DepthTile, its vertices' depths
/// (depths_in_tile) and the thresholds (texel_thresholds_merged): the part
/// TiledSegmentation::run_tile gives, bit for bit. std::nullopt when a region grows past what the
/// tile's halo holds (kTileMeshHaloRadii, 12r): the part then needs the whole mesh. The tile and the depths are taken by value, the depths becoming
/// the tile's depth maps: a caller that moves them in spares a copy. With `read_mesh_again`
/// (the tile's mesh, as read before), the tile's mesh is let go while the regions grow in a
/// narrower cut of it, and read again only if one reaches that cut's edge, to cut around that
/// region: a job then holds a cut without its tile (sphere-1 level 11 at 1% in 16 tiles, tile 6:
/// 1,730 -> 1,269 MB; growing again around the regions rather than in the tile, 918 MB). Throws
/// InvalidInput as first_depth_part, and when the depths or thresholds do not fit, or the mesh read
/// again is not the tile's.
std::optional<TilePart> texel_part_in_tile(DepthTile tile, std::vector<std::vector<double>> depths,
                                           const std::vector<double>& thresholds,
                                           const SegmentationParams& params, const DepthPassOf& of,
                                           const std::function<Mesh()>& read_mesh_again = {});

/// The texels of the texel pass after depth pass `of`, joined from every tile's part of it
/// (part_of) without the mesh or the depth maps, with the run's numbers that any of its tiles
/// carries (a tile without its mesh will do, as pipeline/tile_mesh.hpp's
/// read_tile_mesh_numbers reads it, so that a job holds the joins before its tile). A job that
/// joins them once leaves them in a file for the others (pipeline/joined_texels.hpp), and the
/// join of the outputs takes them from there (TiledSegmentation::finish_texel_pass).
struct JoinedTexels {
    /// Positive, negative: the texels TiledSegmentation merges, but for `face_texel`, left
    /// empty (#F is not in a tile); empty for an orientation the pass does not have.
    std::array<TexelSet, 2> texels;
    /// Positive, negative: each texel's greatest vertex depth (texel_depths), which the rims
    /// compare.
    std::array<std::vector<double>, 2> depth;
};
/// Holds the regions of every part and a few numbers per face of a region, not per face of
/// the mesh. Throws InvalidInput when a part is not its tile's part of that texel pass, the
/// parts' thresholds differ, or their regions and depths do not fit.
JoinedTexels join_texels(const DepthTile& tile, const SegmentationParams& params,
                         const DepthPassOf& of, const TilePartSource& part_of);

/// What the rims pass decided, joined from every tile's part of it: which orientations the
/// second smoothing smooths again, and what each leaves out.
struct JoinedRims {
    /// DepthWithoutRims and the orientations smoothed again, in the run's order (none: the
    /// run has no second smoothing).
    DepthPassOf second;
    /// Positive, negative run: a flag per texel of the other orientation, set for those its
    /// second smoothing leaves out (the texels that make a rim and are not rims).
    std::array<std::vector<char>, 2> use;
};
/// Reads each part once. Throws InvalidInput when a part is not its tile's part of the rims
/// pass or its flags are not one per joined texel of the first texel pass (`texels`).
JoinedRims join_rims(const DepthTile& tile, const JoinedTexels& texels,
                     const SegmentationParams& params, const TilePartSource& part_of);

/// What join_rims decides, from the rims parts alone: each part holds a flag per texel of the
/// whole run, so or-ing them needs no joined texels, and a job that only wants to know whether
/// the second smoothing has anything to do (JoinedRims::second.orientations) learns it without
/// joining them. `tiles` parts, the first's flag counts taken as the run's. Throws InvalidInput
/// when a part is not its tile's part of the rims pass or its flag counts differ from the
/// first's.
JoinedRims join_rims_alone(int tiles, const SegmentationParams& params,
                           const TilePartSource& part_of);

/// A tile's part of the second smoothing's depth pass (TilePass::DepthWithoutRims) from its
/// DepthTile, the joined texels of the first texel pass and the joined rims: the part
/// TiledSegmentation::run_tile gives, bit for bit. Throws InvalidInput as first_depth_part,
/// and when the rims do not fit the texels or have no second smoothing.
TilePart depth_without_rims_part(DepthTile tile, const JoinedTexels& texels, const JoinedRims& rims,
                                 const SegmentationParams& params);

/// The segmentation's texels before the features, numbered as the whole run numbers them
/// (each orientation of the run in turn, without the faces that texels of the orientations
/// before took, and without the texels then smaller than the minimum): the first texel pass's
/// texels (`first`), or for an orientation smoothed again (`rims`), the second's (`second`;
/// empty when the run has no second smoothing). Both are taken by value: their texels move
/// into the result, so that a caller that moves them in does not hold them twice.
std::vector<Texel> segmentation_texels(JoinedTexels first, JoinedTexels second,
                                       const JoinedRims& rims, const SegmentationParams& params);

/// Where the depths of an orientation come from: the last depth pass that smoothed it (the
/// first, or the second smoothing's) and that pass's parts.
struct DepthSource {
    DepthPassOf pass;
    TilePartSource part_of;
    /// Per orientation of the pass: the greatest depth over every tile (0 when none), when the
    /// caller knows it (the sorted depths' headers); empty: taken from every part, each read.
    std::vector<double> greatest;
};

/// A tile's part of the features pass (TilePass::Features) from its DepthTile, the
/// segmentation's texels (segmentation_texels) and the depth parts of each orientation of the
/// run (positive, negative; depths_in_tile picks the tile's, and the greatest depth is the
/// source's, or taken over every part): the part TiledSegmentation::run_tile gives, bit for bit.
/// std::nullopt when a texel whose first face the tile owns, or the curvature discs around it,
/// reach past the tile's halo: the part then needs the whole mesh. The tile is taken by value
/// and let go once cut to the features' halo: a caller that moves it in does not hold it beside
/// the cut. Throws InvalidInput as first_depth_part, and when a depth source lacks its
/// orientation or its parts do not fit.
std::optional<TilePart> features_part(DepthTile tile, const std::vector<Texel>& texels,
                                      const std::array<DepthSource, 2>& depths,
                                      const SegmentationParams& params);

/// Whether the run has a rims pass: rims are removed, and both orientations have texels.
bool rims_needed(const JoinedTexels& texels, const SegmentationParams& params);

/// A tile's part of the rims pass (TilePass::Rims) from its DepthTile and the joined texels:
/// the part TiledSegmentation::run_tile gives, bit for bit. The tile is cut to the depth halo
/// first, as first_depth_part cuts it. Throws InvalidInput as first_depth_part, and when the
/// texels' depths do not match the texels.
TilePart rims_part(DepthTile tile, const JoinedTexels& texels, const SegmentationParams& params);

}  // namespace geotex
