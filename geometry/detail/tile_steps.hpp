#pragma once
// The steps of a tile that both the tiled depth maps and texels (tiles.cpp) and the tiled
// segmentation's passes (tiled_segmentation.cpp) run: what a tile takes from the whole mesh,
// its depths, and its texel regions.

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/disc_means.hpp"
#include "geometry/tiled_segmentation.hpp"
#include "geometry/tiles.hpp"
#include "geometry/topology.hpp"

namespace geotex::detail {

/// The values of `whole` (one per vertex or face of the whole mesh) at the ids in `ids`.
template <class T>
std::vector<T> restricted(const std::vector<T>& whole, const std::vector<int>& ids) {
    std::vector<T> out(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) out[i] = whole[static_cast<std::size_t>(ids[i])];
    return out;
}

/// What the tile passes take from the whole mesh: which discs are sampled, where the sampling
/// grid starts, and which vertices are one connected piece.
struct WholeMeshChoices {
    DiscSampling sampling;
    VertexComponents components;
};
WholeMeshChoices whole_mesh_choices(const Mesh& mesh, const SmoothingParams& params);

/// The vertices a tile leaves out of its smoothing of one orientation (#V_tile; empty: none).
using TileExclusion =
    std::function<std::vector<char>(const MeshTile&, const MeshTopology&, DetailOrientation)>;

/// The orientations of a tiled run's first depth pass.
std::vector<DetailOrientation> first_depth_orientations(const SegmentationParams& params);

/// Throws InvalidInput about tile `tile`'s part of `pass` ("does not fit this run: what")
/// unless `ok`.
void expect_part(bool ok, TilePass pass, int tile, const std::string& what);

/// Whether `ids` ascend strictly within [0, size).
bool ascending_ids(const std::vector<int>& ids, int size);

/// Throws InvalidInput unless `part` is tile `tile`'s part of depth pass `pass`, with the
/// depths of `n` orientations over ascending vertex ids below `num_vertices`.
void expect_depth_part(const TilePart& part, TilePass pass, int tile, std::size_t n,
                       int num_vertices);

/// Tile `b` with a halo `halo` wide and the whole mesh's choices at its vertices (`known` as
/// make_mesh_tile's).
DepthTile make_depth_tile(const Mesh& mesh, const TileBoxes& boxes, int b, double halo,
                          double radius, const WholeMeshChoices& whole,
                          const MeshBoxes* known = nullptr);

/// `tile` cut to a narrower `halo` (<= tile.halo): the tile make_depth_tile gives with that
/// halo, bit for bit.
DepthTile narrowed_depth_tile(const DepthTile& tile, double halo);

/// A tile's depth of each orientation at the vertices it owns (TilePart's depth members); with
/// `exclude` set, the vertices it gives are left out of each orientation's smoothing (the
/// second smoothing of the rim removal); with `count`, the fast mode's counts are taken too.
/// Taken by value: its components move into the depth mapper instead of being copied.
TilePart depth_part(DepthTile tile, const SmoothingParams& params,
                    const std::vector<DetailOrientation>& orientations,
                    const TileExclusion& exclude, bool count);

/// Depth maps of the orientations over the mesh's vertices, all zero, for make_tiled_depth_maps
/// to fill with every tile's depth part (TiledSegmentation makes its maps as parts join).
std::vector<DepthMap> empty_depth_maps(const Mesh& mesh,
                                       const std::vector<DetailOrientation>& orientations);

/// Writes a depth part's values into the maps (one per orientation of its pass).
void add_depth_part(const TilePart& part, std::vector<DepthMap*> maps);

/// Tile `b`'s texel regions of each depth map (over `mesh`, and in its ids) with the whole
/// mesh's thresholds: the regions of the seeds it owns, grown with a halo of at least `width`,
/// doubled while a region reaches the halo's edge. `mesh` is the whole mesh, or a tile of it
/// with a halo `max_width` wide: std::nullopt when a region would need a halo wider than that.
std::optional<std::vector<TexelRegions>> texel_part(
    const Mesh& mesh, const std::vector<const DepthMap*>& depth,
    const std::vector<double>& thresholds, const TexelParams& params, const TileBoxes& boxes, int b,
    double width, double max_width = std::numeric_limits<double>::infinity());

/// Renumbers regions grown in a tile into the ids of what it was cut from: a seed v becomes
/// vertex[v], a face f face[f].
void renumber_regions(std::vector<TexelRegions>& regions, const std::vector<int>& vertex,
                      const std::vector<int>& face);

/// The texels of a depth map from the regions of every tile, merged as make_texels merges.
TexelSet merge_tile_regions(TexelRegions all, const DepthMap& depth, const TexelParams& params,
                            double threshold);

}  // namespace geotex::detail
