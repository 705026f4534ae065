#pragma once
// The steps of a tile that the tiled depth maps (tiles.cpp) and texels (tile_texels.cpp), the tiled
// segmentation's passes (tiled_segmentation.cpp) and the jobs that make a tile's parts alone
// (tile_alone.cpp) run: what a tile takes from the whole mesh, its depths (tiles.cpp) and
// texel regions (tile_texels.cpp), its rims and feature rows, and the checks of a part read back
// (tile_part_steps.cpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "geometry/disc_means.hpp"
#include "geometry/rims.hpp"
#include "geometry/texels.hpp"
#include "geometry/tiled_segmentation.hpp"
#include "geometry/tiles.hpp"
#include "geometry/topology.hpp"

namespace geotex::detail {

/// Where an orientation's depth map, texels and flags go in a tiled run's pairs: positive 0,
/// negative 1.
inline std::size_t index_of(DetailOrientation o) {
    return o == DetailOrientation::Positive ? 0 : 1;
}

/// Where `id` is in `ascending` (a tile's ids of the whole mesh's vertices or faces, or any
/// strictly ascending ids), or -1 when it is not there.
inline int index_in(const std::vector<int>& ascending, int id) {
    const auto it = std::lower_bound(ascending.begin(), ascending.end(), id);
    return it != ascending.end() && *it == id ? static_cast<int>(it - ascending.begin()) : -1;
}

/// The values of `whole` (one per vertex or face of the whole mesh: a vector, or a
/// PositionSpan) at the ids in `ids`.
template <class Values>
auto restricted(const Values& whole, const std::vector<int>& ids) {
    std::vector<std::decay_t<decltype(whole[0])>> out(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) out[i] = whole[static_cast<std::size_t>(ids[i])];
    return out;
}

/// The tile of `mesh` made of the faces `taken` marks (#F; 2: owned, 1: taken, 0: left out),
/// with their vertices in the mesh's order, flagged owned where `where` (#V) is 1 and complete
/// where it is not 0: make_mesh_tile's gathering, for cuts decided otherwise too.
MeshTile gathered_tile(const Mesh& mesh, const std::vector<char>& where,
                       const std::vector<char>& taken);

/// What the tile passes take from the whole mesh: which discs are sampled, where the sampling
/// grid starts, and which vertices are one connected piece.
struct WholeMeshChoices {
    DiscSampling sampling;
    VertexComponents components;
};
WholeMeshChoices whole_mesh_choices(const Mesh& mesh, const SmoothingParams& params);

/// The same for a mesh whose `num_faces` faces are read a block at a time.
WholeMeshChoices whole_mesh_choices(PositionSpan positions, const FaceBlockReader& faces,
                                    std::size_t num_faces, const SmoothingParams& params);

/// The whole mesh's choices with their values at each vertex in a scratch file, read through
/// its mapping: what the mesh job of a tiled run reads at the vertices of each tile it spools.
/// The file's pages go again when memory is short and come back as a tile reads them, where
/// WholeMeshChoices' arrays (5 bytes a vertex, 210 MB at sphere-1 level 11) would stay held
/// beside the page cache the cutting reads the positions through. The values are numbered as
/// the tiler numbers the vertices, so that a tile cut in the order of space reads those of a
/// piece of space.
class SpooledChoices {
  public:
    /// `whole`'s values at vertex ids[k] for k in [0, num_vertices) (at vertex k when `ids` is
    /// null), written to a scratch file in `dir` (IoError naming it).
    SpooledChoices(const WholeMeshChoices& whole, const int* ids, std::size_t num_vertices,
                   const std::string& dir);
    bool fast(std::size_t k) const { return values_[k] < 0; }
    int component(std::size_t k) const { return values_[k] < 0 ? ~values_[k] : values_[k]; }
    /// The choices without their values at the vertices: the sampling grid and the number of
    /// components.
    const WholeMeshChoices& outline() const { return outline_; }

  private:
    ScratchFile file_;  // a vertex's component, complemented (~c) when its discs are sampled
    const int* values_ = nullptr;
    WholeMeshChoices outline_;
};

/// The rows of a spooled tile (StreamTiler::spool) with the whole mesh's choices at its
/// vertices (`choices` numbered as the tiler that spooled it), for write_tile_mesh; both must
/// outlive them (geometry/depth_tile_rows.cpp).
std::unique_ptr<DepthTileRows> spooled_rows(const SpooledTile& tile, const SpooledChoices& choices);

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

/// Throws InvalidInput unless `part` is tile `tile`'s part of texel pass `pass`, with the
/// regions, their depths and the thresholds of `n` orientations, its seeds below
/// `num_vertices` and its faces ascending below `num_faces`.
void expect_texel_part(const TilePart& part, TilePass pass, int tile, std::size_t n,
                       int num_vertices, int num_faces);

/// Cell index of coordinate x along an axis cut into n equal parts from lo to hi, clamped so
/// that the mesh's own extremes fall into the first and last part.
/// Inline: box_of calls it for every vertex and face of the mesh, three times each.
inline int cell_of(double x, double lo, double hi, int n) {
    if (n == 1 || !(hi > lo)) return 0;
    const double k = std::floor((x - lo) / (hi - lo) * n);
    return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
}

/// The box of face f's centroid, (a + b + c) / 3: the box that owns the face.
int face_box(const Mesh& mesh, const TileBoxes& boxes, int f);
/// The same for a face with corners `fv` in `positions`.
int face_box(PositionSpan positions, const TileBoxes& boxes, const std::array<int, 3>& fv);

/// Throws InvalidInput unless `index` is one of the boxes and `halo` is >= 0 and finite.
void check_tile_request(const TileBoxes& boxes, int index, double halo);

/// Tile `b` with a halo `halo` wide and the whole mesh's choices at its vertices, cut by
/// `tiler` when given (a tiler of this mesh and these boxes), else by make_mesh_tile.
DepthTile make_depth_tile(const Mesh& mesh, const TileBoxes& boxes, int b, double halo,
                          double radius, const WholeMeshChoices& whole, MeshTiler* tiler = nullptr);
/// The same for tile `tile` of a mesh of `num_vertices` vertices, cut already (tile.face and
/// tile.vertex are ids of that mesh) with a halo `halo` wide.
DepthTile make_depth_tile(MeshTile tile, int num_vertices, const TileBoxes& boxes, int b,
                          double halo, double radius, const WholeMeshChoices& whole);

/// `tile` cut to a narrower `halo` (<= tile.halo): the tile make_depth_tile gives with that
/// halo, bit for bit.
DepthTile narrowed_depth_tile(const DepthTile& tile, double halo);

/// A tile's depth of each orientation at the vertices it owns (TilePart's depth members); with
/// `exclude` set, the vertices it gives are left out of each orientation's smoothing (the
/// second smoothing of the rim removal); with `count`, the fast mode's counts are taken too.
/// Taken by value: its components move into the depth mapper instead of being copied, and its
/// ids in the whole mesh are let go before the smoothing.
TilePart depth_part(DepthTile tile, const SmoothingParams& params,
                    const std::vector<DetailOrientation>& orientations,
                    const TileExclusion& exclude, bool count);

/// Depth maps of the orientations over the mesh's vertices, all zero, for make_tiled_depth_maps
/// to fill with every tile's depth part (TiledSegmentation makes its maps as parts join).
std::vector<DepthMap> empty_depth_maps(const Mesh& mesh,
                                       const std::vector<DetailOrientation>& orientations);

/// Writes a depth part's values into the maps (one per orientation of its pass).
void add_depth_part(const TilePart& part, std::vector<DepthMap*> maps);

/// Tile `b`'s part of a texel pass: its texel regions of each depth map (over `mesh`, and in
/// its ids) with the whole mesh's thresholds, and their depths. The regions of the seeds it owns
/// grow first in its box with a halo `width` wide (at least 3r, kTexelHaloRadii, which the
/// seeds' discs want); the seed of a region that reaches that halo's edge grows again in a cut
/// of `mesh` around the region alone (its faces' box, with a margin of at least 3r), the margin
/// doubled while the region reaches that cut's edge. `mesh` is the whole mesh, or the mesh of
/// `mesh_tile`, a tile of it with a halo `max_width` wide: std::nullopt when a region reaches
/// that tile's edge (a vertex not complete in it), or when `width` is wider than `max_width`.
/// Each cut makes its faces' depths from its vertex depths where the map has none (the same
/// bits). With `read_mesh_again` too, the tile's mesh is released while the regions grow in the
/// first cut, and read again (assigned to mesh_tile->mesh, which `mesh` refers to) only if a
/// seed is to grow again: a tile job then holds a cut without its tile. The part's pass is left
/// to the caller.
std::optional<TilePart> texel_part(const Mesh& mesh, const std::vector<const DepthMap*>& depth,
                                   const std::vector<double>& thresholds, const TexelParams& params,
                                   const TileBoxes& boxes, int b, double width,
                                   double max_width = std::numeric_limits<double>::infinity(),
                                   MeshTile* mesh_tile = nullptr,
                                   const std::function<Mesh()>& read_mesh_again = {});

/// Renumbers regions grown in a tile into the ids of what it was cut from: a seed v becomes
/// vertex[v], a face f face[f].
void renumber_regions(std::vector<TexelRegions>& regions, const std::vector<int>& vertex,
                      const std::vector<int>& face);

/// The texels of a depth map from the regions of every tile, merged as make_texels merges.
TexelSet merge_tile_regions(TexelRegions all, const DepthMap& depth, const TexelParams& params,
                            double threshold);

/// The texel regions of one orientation from every tile's texel part, and the depths the
/// parts carry, joined as the parts are read and then merged as merge_tile_regions merges them
/// over the depth maps, without those maps. A tiled run's jobs after the texel pass hold this
/// for the whole mesh, so it keeps each face a part's regions claim once, with its two depths,
/// rather than each region face's depths (the regions of a detail's seeds overlap: about
/// eight claims a face at 1% on sphere-1), and of each region's touch list only the faces next
/// to it, its own being in its face list.
class TexelRegionJoin {
  public:
    /// Adds one part's regions and the depths it carries for them. Throws InvalidInput when the
    /// depths do not match the regions, or give one face two depths.
    void add(TexelRegions regions, RegionDepths depths);

    /// The texels: merge_tile_regions' but for `face_texel`, left empty (#F is not known), with
    /// each texel's greatest vertex depth (texel_depths) in `texel_depth`. Empties the join.
    /// Throws InvalidInput when two regions have one seed or two parts give a face different
    /// depths.
    TexelSet merge(const TexelParams& params, DetailOrientation orientation, double threshold,
                   std::vector<double>& texel_depth);

  private:
    std::vector<TexelRegion> regions_;
    std::vector<double> seed_depth_;  // one per region
    int num_seeds_ = 0;
    // The faces the regions claim, with their depth and greatest vertex depth: the first
    // `unique_faces_` ascending and once each, then each part's since, the same.
    std::vector<int> face_;
    std::vector<double> face_depth_, face_peak_;
    std::size_t unique_faces_ = 0;
};

/// Ors tile `tile`'s part of the rims pass into `flags` (one per texel of each orientation).
/// Throws InvalidInput when it is another pass's or tile's, or its flags are not one per texel.
void add_rim_part(const TilePart& part, int tile, RimFlags& flags);

/// What the rims pass decides, from the rim flags of the whole mesh: for each orientation of
/// `runs`, the texels of the other orientation that its second smoothing leaves out (those
/// that make a rim and are not rims), indexed by the run's orientation (positive 0, negative
/// 1); how many for each run (`counts`), and the runs with any, in their order (`again`).
std::array<std::vector<char>, 2> rim_exclusions(const RimFlags& flags,
                                                const std::vector<DetailOrientation>& runs,
                                                std::vector<int>& counts,
                                                std::vector<DetailOrientation>& again);

/// The second smoothing's exclusion of a tile (depth_part's `exclude`): for each orientation,
/// the vertices near the texels of the other orientation that `use` flags (rim_exclusions), as
/// make_rims leaves them out. Holds pointers to `texels` and `use`, which must outlive it.
TileExclusion rim_exclusion(const std::array<const TexelSet*, 2>& texels,
                            const std::array<std::vector<char>, 2>& use, const RimParams& params);

/// The features pass's part for the texels `ids` of `texels` (the segmentation's, with the
/// whole mesh's face ids): their curvature and unnormalised feature rows over `tile` (with the
/// whole mesh's ids, and a halo that holds the texels and the curvature discs of radius `rho`
/// around them), with each orientation's depth map at the tile's vertices and faces (null: the
/// run has none; its greatest depth the whole map's). Throws InvalidInput when a texel's face
/// is not in the tile.
TilePart feature_part(const MeshTile& tile, const std::vector<Texel>& texels,
                      const std::vector<int>& ids, const DepthMap* positive,
                      const DepthMap* negative, double largest_side, double rho);

/// The texels of `whole` (faces of the whole mesh) as far as they lie in `tile`: the same
/// texels, with the faces the tile holds in its ids (the rims read nothing else).
TexelSet texels_in_tile(const TexelSet& whole, const MeshTile& tile);

/// make_rims' flags counted at the vertices `tile` owns, from the whole mesh's texels and their
/// greatest vertex depths (texel_depths); or-ed over the tiles they are the whole mesh's.
RimFlags rim_part(const MeshTile& tile, const std::array<const TexelSet*, 2>& texels,
                  const std::array<const std::vector<double>*, 2>& texel_depth,
                  const RimParams& params);

}  // namespace geotex::detail
