#pragma once
/// Spatial tiles of a mesh (issue 21, item 3; docs/tiles.md): a mesh cut into boxes, each with
/// a halo of the faces around it, so that a scan larger than memory, or one spread over several
/// machines, is segmented a tile at a time. What a tile computes for the vertices of its box
/// equals what the whole mesh gives them when the halo is wide enough and the tile takes the
/// few choices that depend on the whole mesh from it (the fast mode's sampling, the connected
/// components): this header gives the boxes, the tiles, the depth maps and texels made tile by
/// tile, and the whole segmentation in tiles, in one call or a pass at a time for separate jobs.

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "geometry/curvature.hpp"
#include "geometry/depth_map.hpp"
#include "geometry/enum_names.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/mesh.hpp"
#include "geometry/rims.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/smoothed_surface.hpp"
#include "geometry/texels.hpp"

namespace geotex {

/// The mesh's bounding box cut into count[0] x count[1] x count[2] equal boxes.
struct TileBoxes {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero();
    Eigen::Vector3d hi = Eigen::Vector3d::Zero();
    std::array<int, 3> count{1, 1, 1};

    int size() const { return count[0] * count[1] * count[2]; }
    /// The box holding `p`, by the cell index along each axis (below lo: the first, from hi
    /// on: the last), so that every point has exactly one.
    int box_of(const Eigen::Vector3d& p) const;
    /// Euclidean distance from `p` to box `b` (0 inside).
    double distance(int b, const Eigen::Vector3d& p) const;
};

/// `count` boxes (>= 1) over the mesh's bounding box: its longest side cut into nx and the
/// second longest into ny parts, nx * ny = count with nx >= ny as near each other as count
/// allows (4: 2 x 2, 9: 3 x 3, 6: 3 x 2). Throws InvalidInput on a count below 1 or a mesh
/// without vertices.
TileBoxes make_tile_boxes(const Mesh& mesh, int count);

/// One tile: the faces of the whole mesh with a vertex within the halo of its box or their
/// centroid in it, and their vertices, renumbered in the whole mesh's order.
struct MeshTile {
    Mesh mesh;                       ///< the tile's faces over its own vertex numbers
    std::vector<int> vertex;         ///< #V_tile: the vertex's id in the whole mesh, ascending
    std::vector<int> face;           ///< #F_tile: the face's id in the whole mesh, ascending
    std::vector<char> owned_vertex;  ///< #V_tile: the vertex lies in the tile's box
    std::vector<char> owned_face;    ///< #F_tile: the face's centroid lies in the tile's box
    /// #V_tile: the vertex lies within the halo of the box, so every face around it in the
    /// whole mesh is in the tile; a walk over such vertices sees what the whole mesh has.
    std::vector<char> complete_vertex;
};

/// Tile `index` of `boxes` with a halo `halo` wide (>= 0, mesh units). Every face of the mesh
/// is owned by one tile, and every vertex of a face by one. The halo is measured in space, so
/// it holds every vertex within that geodesic distance of the box too. Throws InvalidInput
/// on an index out of range or a halo that is negative or not finite.
MeshTile make_mesh_tile(const Mesh& mesh, const TileBoxes& boxes, int index, double halo);

/// The halo, in multiples of r, that make_tiled_depth_maps leaves around each box by default:
/// twicing averages disc means of disc means, each at most 2r wide with the fast mode's
/// interpolation, so the first smoothing needs 4r (bit-equal depths at 4r on the mixed
/// inscription, 2e-11 off at 3r); the rim removal's second smoothing moves each vertex along a
/// disc-averaged normal, one disc more, and 4r is not enough there (docs/tiles.md).
constexpr double kDepthHaloRadii = 6;

/// The depth map of each orientation in `orientations` over the whole mesh, computed tile by
/// tile: each tile is smoothed with the whole mesh's sampling and measured against its own
/// part of the smoothed surface within its vertices' components of the whole mesh, and gives
/// the depths of the vertices it owns. Equal to make_depth_map on the whole mesh (to
/// rounding: the disc sums of a tile may add in another order) when `halo` is wide enough;
/// `halo` 0 takes kDepthHaloRadii * r. Only one tile's topology and discs are held at a
/// time. Throws InvalidInput as make_smoothed_surface and make_tile_boxes.
std::vector<DepthMap> make_tiled_depth_maps(const Mesh& mesh, const SmoothingParams& params,
                                            const std::vector<DetailOrientation>& orientations,
                                            int tiles, double halo = 0);

/// The halo, in multiples of r, that make_tiled_texels leaves around each box by default: a
/// seed is a local maximum over its disc of r and its threshold is Otsu's over its disc of 2r.
constexpr double kTexelHaloRadii = 3;

/// The texels of each depth map in `depth` (#V and #F of the whole mesh each, e.g. from
/// make_tiled_depth_maps) computed tile by tile: the seeds' threshold is the whole mesh's,
/// each tile grows the regions of the seeds it owns, and the regions of every tile are merged
/// as make_texels merges them. Equal to make_texels on the whole mesh, whose topology is never
/// built. `halo` 0 takes kTexelHaloRadii * r; a tile where a region reaches the edge of its
/// halo is made again with twice the halo, so a texel larger than the halo costs memory, not
/// exactness. Throws InvalidInput as make_texels.
std::vector<TexelSet> make_tiled_texels(const Mesh& mesh, const std::vector<DepthMap>& depth,
                                        const TexelParams& params, int tiles, double halo = 0);

/// The passes of a tiled segmentation, in their order (docs/tiles.md). Every tile runs a pass,
/// and the tiles' parts are joined before the next pass starts; a pass the mesh does not need
/// (the rims with --keep-rims, the second smoothing when no detail is left out) is skipped.
enum class TilePass { Depth, Texels, Rims, DepthWithoutRims, TexelsWithoutRims, Features, Done };
inline constexpr std::array<std::pair<const char*, TilePass>, 7> kTilePassNames = {{
    {"depth", TilePass::Depth},
    {"texels", TilePass::Texels},
    {"rims", TilePass::Rims},
    {"depth-without-rims", TilePass::DepthWithoutRims},
    {"texels-without-rims", TilePass::TexelsWithoutRims},
    {"features", TilePass::Features},
    {"done", TilePass::Done},
}};
inline const char* name_of(TilePass p) { return name_in(kTilePassNames, p); }

/// What one tile gives to one pass (TiledSegmentation::run_tile); only the members of its pass
/// are set. Ids are the whole mesh's.
struct TilePart {
    TilePass pass = TilePass::Depth;
    int tile = 0;
    // Depth passes.
    std::vector<int> vertices;                ///< the vertices the tile owns, ascending
    std::vector<std::vector<double>> depths;  ///< per orientation of the pass: #vertices depths
    std::vector<int> moved;  ///< per orientation: how many of the vertices stand out (eq. 2)
    int interpolated = 0;    ///< fast discs: vertices interpolated (first depth pass only)
    int samples = 0;         ///< fast discs: vertices sampled (first depth pass only)
    // Texel passes.
    std::vector<TexelRegions> regions;  ///< per orientation: the regions of the seeds it owns
    // Rims.
    RimFlags rims;  ///< the flags counted at the vertices it owns, #texels of each orientation
    // Features.
    std::vector<int> texels;              ///< the texels whose first face it owns, ascending
    FeatureRows rows;                     ///< one row per texel of `texels`, not normalised
    std::vector<int> curvature_vertices;  ///< the vertices of those texels, ascending
    CurvatureField curvature;             ///< #curvature_vertices values of each field
};

/// Tiles (0-based) as the 1-based numbers a user sees, at most ten of them: "1, 2, 7" or
/// "1, 2, ..., 10 and 6 more".
std::string tile_numbers(const std::vector<int>& tiles);

/// run_tiled_segmentation one pass and one tile at a time, for tiles run as separate jobs
/// (`geotex segment --tiles N --tile-dir DIR --pass P`): each job makes one pass's part of some
/// tiles, and the next pass (or the merge) joins the parts of every tile with add() and
/// finish_pass(). The parts are deterministic, so that a job that rebuilds the state of the
/// passes before its own, from the parts on disk, holds what every other job holds. Holds a
/// reference to `mesh`, which must outlive it.
///
///     TiledSegmentation run(mesh, params, tiles);
///     while (run.pass() != TilePass::Done) {
///         for (int b = 0; b < run.num_tiles(); ++b) run.add(run.run_tile(b));
///         run.finish_pass();
///     }
///     Segmentation seg = std::move(run).result();
class TiledSegmentation {
  public:
    /// Throws InvalidInput as run_tiled_segmentation.
    TiledSegmentation(const Mesh& mesh, const SegmentationParams& params, int tiles);
    ~TiledSegmentation();
    TiledSegmentation(TiledSegmentation&&) noexcept;
    TiledSegmentation& operator=(TiledSegmentation&&) noexcept;

    int num_tiles() const;
    /// The pass whose parts are awaited; Done when the segmentation is complete.
    TilePass pass() const;
    /// The orientations of the current depth or texel pass, in the order of a part's lists.
    const std::vector<DetailOrientation>& orientations() const;
    /// Tile `tile`'s part of the current pass (tile in [0, num_tiles())). May be called for
    /// several tiles at once from different threads.
    TilePart run_tile(int tile) const;
    /// Joins a part of the current pass. Throws InvalidInput when it is of another pass, its
    /// tile's part is in already, or its sizes or ids do not fit the mesh and the pass.
    void add(TilePart part);
    /// The tiles whose part of the current pass is not in yet, ascending.
    std::vector<int> missing() const;
    /// Joins the parts of the pass and moves to the next pass the mesh needs. Throws
    /// InvalidInput naming the missing tiles when some part is not in.
    void finish_pass();
    /// The segmentation, once pass() is Done (else throws InvalidInput).
    Segmentation result() &&;

  private:
    struct State;
    std::unique_ptr<State> state_;
};

/// run_segmentation a tile at a time (docs/tiles.md): the depth maps and texels as
/// make_tiled_depth_maps and make_tiled_texels make them, the rim removal's flags or-ed over
/// the tiles, the second smoothing in tiles, then the curvature and feature rows of each texel
/// in the tile that owns its first face, normalised and clustered once. The same texels,
/// features and textures as run_segmentation, to the rounding of a tile's disc sums. Only one
/// tile's topology, discs and trees are held at a time; the whole mesh and a few arrays a
/// vertex and a face stay (the metrics' arrays are made at the end, for the result).
/// Differences: `topology` is empty; with rim removal (the default) both orientations are
/// always computed, where the whole run's rim check may spare one. Throws InvalidInput as
/// run_segmentation, on a count of tiles below 1, and on a mesh whose size is beyond 2^+-32 units
/// (the whole run's unit frame; scale it first). The observer hears of each pass
/// (TiledSegmentation's passes, one after another) as a stage, and of each tile within it as a
/// stage begun and never finished ("texels (tiles): tile 3/16"), which a terminal shows in place.
Segmentation run_tiled_segmentation(const Mesh& mesh, const SegmentationParams& params, int tiles,
                                    const StageObserver& observer = {});

}  // namespace geotex
