#pragma once
/// The whole segmentation in spatial tiles (issue 21, item 3; docs/tiles.md): the passes of
/// run_segmentation made a tile at a time with the tiles of tiles.hpp, in one call
/// (run_tiled_segmentation) or a pass and a tile at a time for separate jobs
/// (TiledSegmentation, whose parts pipeline/tile_parts.hpp writes and reads).

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "geometry/curvature.hpp"
#include "geometry/disc_means.hpp"
#include "geometry/enum_names.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/rims.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/tiles.hpp"
#include "geometry/topology.hpp"

namespace geotex {

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
/// Whether pass `p` makes depth maps (the first smoothing's or the second's).
inline bool is_depth_pass(TilePass p) {
    return p == TilePass::Depth || p == TilePass::DepthWithoutRims;
}
/// Whether pass `p` grows and merges texel regions (after the first smoothing or the second).
inline bool is_texel_pass(TilePass p) {
    return p == TilePass::Texels || p == TilePass::TexelsWithoutRims;
}

/// What the merge of a tile's texel regions and the rims read of the depth maps, carried by a
/// texel part so that a job merges the texels of every tile without the depth maps
/// (join_texels): each region's seed depth, and the depth and the greatest vertex depth
/// of each face of each region.
struct RegionDepths {
    std::vector<double> seed;  ///< #regions
    std::vector<double> face;  ///< the faces of every region, one region after another
    std::vector<double> peak;  ///< the same faces: the greatest depth of their three vertices
};

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
    std::vector<TexelRegions> regions;        ///< per orientation: the regions of the seeds it owns
    std::vector<RegionDepths> region_depths;  ///< per orientation: the depths at those regions
    std::vector<double> thresholds;  ///< per orientation: the pass's seed threshold (every tile's)
    // Rims.
    RimFlags rims;  ///< the flags counted at the vertices it owns, #texels of each orientation
    // Features.
    std::vector<int> texels;              ///< the texels whose first face it owns, ascending
    FeatureRows rows;                     ///< one row per texel of `texels`, not normalised
    std::vector<int> curvature_vertices;  ///< the vertices of those texels, ascending
    CurvatureField curvature;             ///< #curvature_vertices values of each field
};

/// What a run kept for its outputs (TiledResult::Outputs) takes of a tile's depth part: each
/// orientation's greatest depth (0 when none is above it) and moved vertices, and the first
/// pass's counts. The file beside the part carries it (pipeline/sorted_depths.hpp), so that
/// the join reads it instead of the part.
struct DepthPartSummary {
    int tile = 0;                  ///< 0-based
    std::vector<double> greatest;  ///< per orientation of the pass, in the part's order
    std::vector<int> moved;        ///< per orientation
    int interpolated = 0;          ///< as TilePart
    int samples = 0;               ///< as TilePart
};

/// What the depth passes of one tile take from the whole mesh: the tile with a halo of at least
/// the depth halo (kDepthHaloRadii r), the whole mesh's choices at its vertices, and the run's
/// numbers. The mesh job of a tiled run writes each tile's (pipeline/tile_mesh.hpp), so that
/// the jobs of the passes read their tile instead of the whole mesh (tile_alone.hpp).
struct DepthTile {
    int tile = 0;                 ///< 0-based, one of `boxes`
    TileBoxes boxes;              ///< the run's
    int mesh_vertices = 0;        ///< #V of the whole mesh
    double radius = 0;            ///< the run's r, mesh units
    double halo = 0;              ///< of `mesh`, mesh units, >= kDepthHaloRadii * radius
    MeshTile mesh;                ///< the tile's faces and vertices, with that halo
    DiscSampling sampling;        ///< the whole mesh's, `fast` at the tile's #V_tile vertices
    VertexComponents components;  ///< the whole mesh's, at the tile's #V_tile vertices
};

/// A DepthTile's arrays read a value or a block at a time, for writing a tile whether or not
/// it is held: the mesh job of a tiled run writes tiles it never holds whole
/// (TiledSegmentation::spool_depth_tile); held_rows gives a held tile's.
class DepthTileRows {
  public:
    virtual ~DepthTileRows() = default;
    virtual std::size_t num_vertices() const = 0;
    virtual std::size_t num_faces() const = 0;
    /// Vertex k's position, id in the whole mesh, and what mesh.owned_vertex,
    /// mesh.complete_vertex, sampling.fast and components.component hold for it.
    virtual Eigen::Vector3d position(std::size_t k) const = 0;
    virtual int vertex_id(std::size_t k) const = 0;
    virtual bool owned_vertex(std::size_t k) const = 0;
    virtual bool complete_vertex(std::size_t k) const = 0;
    virtual bool fast(std::size_t k) const = 0;
    virtual int component(std::size_t k) const = 0;
    /// Calls fn(block) for the faces in order (mesh.mesh.faces, mesh.face, mesh.owned_face).
    virtual void for_each_face_block(const std::function<void(const TileFaceBlock&)>& fn) const = 0;
};

/// The rows of `tile`, which must outlive them.
std::unique_ptr<DepthTileRows> held_rows(const DepthTile& tile);

/// Tiles (0-based) as the 1-based numbers a user sees, at most ten of them: "1, 2, 7" or
/// "1, 2, ..., 10 and 6 more".
std::string tile_numbers(const std::vector<int>& tiles);

/// What a TiledSegmentation holds, and its result() beside the texels, their features and
/// textures.
enum class TiledResult {
    /// All that run_segmentation gives but the topology: the depth maps, the metrics' normals
    /// and areas, and the curvature at the vertices of texels, in arrays over every vertex and
    /// face. Such a run can also make the parts (run_tile).
    Whole,
    /// What a segmentation's output files read (the JSON report, and the PLY's labels through
    /// FaceLabelCursor), for the join of a tiled run's jobs: the depth maps hold their
    /// greatest depth and moved vertices but no array, `metrics` the extent alone
    /// (make_mesh_extent), and `curvature`, `face_texel`, `face_texture` and the texel sets'
    /// `face_texel` are empty. The texels are merged with the depths their parts
    /// carry, and the seeds' thresholds taken from the parts. About 60 bytes a face fewer
    /// with one orientation (5 GB at sphere-1 level 11). It joins parts and makes none:
    /// run_tile throws.
    Outputs,
};

/// What the join of a tiled run's parts (TiledResult::Outputs) reads of a mesh whose faces it
/// does not hold: the positions, the extent, and the faces it looks up, the first of each
/// texel. The faces stay on disk (pipeline/prepared_mesh.hpp), 12 bytes a face.
struct MeshOutline {
    /// The mesh's positions (#V), held or mapped from a file. Must outlive the run.
    PositionSpan positions;
    /// make_mesh_extent of the whole mesh (MeshExtentSum), num_faces included.
    MeshMetrics extent;
    /// The faces of the ids given (ascending, each below extent.num_faces), in their order.
    std::function<std::vector<std::array<int, 3>>(const std::vector<int>& ids)> faces;
    /// All the faces, a block at a time, for depth_tile(): the mesh job of a tiled run cuts
    /// the tiles of a mesh it keeps on disk. A run that only joins leaves it out.
    FaceBlockReader blocks;
    /// Optional, for depth_tile(): the mesh with its vertices numbered by their places in the
    /// order of space (SpaceOrderedPositions: its copy(), the faces of faces_in_places, and its
    /// ids()), from which the tiles are then cut (StreamTiler).
    struct Placed {
        PositionSpan positions;
        FaceBlockReader faces;
        const int* vertex_ids = nullptr;
    } placed;
};

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
    TiledSegmentation(const Mesh& mesh, const SegmentationParams& params, int tiles,
                      TiledResult result = TiledResult::Whole);
    /// A run kept for its outputs (TiledResult::Outputs) over a mesh whose faces it does not
    /// hold. Throws as the constructor above.
    TiledSegmentation(const MeshOutline& outline, const SegmentationParams& params, int tiles);
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
    /// What tile `tile` takes from the whole mesh (tile in [0, num_tiles())) with a halo of
    /// kTileMeshHaloRadii r, for the functions of tile_alone.hpp in a job that does not hold
    /// the whole mesh. Over a MeshOutline, each tile is a pass over its blocks (StreamTiler);
    /// throws std::invalid_argument when it has none.
    DepthTile depth_tile(int tile) const;
    /// depth_tile(tile) of a run over a MeshOutline given to `use` without being held: its
    /// numbers (a DepthTile whose arrays are empty) and its rows, whose faces wait in a scratch
    /// file in `scratch_dir` (StreamTiler::spool) and whose vertices' values are read from the
    /// positions and the whole mesh's choices, which the first call makes and keeps in a
    /// scratch file there, 4 bytes a vertex read through its mapping. The same values as
    /// depth_tile(tile); holds 12 bytes a vertex of the tile where that holds the tile, 35
    /// bytes a vertex and 17 a face.
    /// Throws as depth_tile, std::invalid_argument for a run over a Mesh, and IoError naming
    /// `scratch_dir`.
    void spool_depth_tile(
        int tile, const std::string& scratch_dir,
        const std::function<void(const DepthTile& numbers, const DepthTileRows& rows)>& use) const;
    /// Joins a part of the current pass. Throws InvalidInput when it is of another pass, its
    /// tile's part is in already, or its sizes or ids do not fit the mesh and the pass.
    void add(TilePart part);
    /// The tiles whose part of the current pass is not in yet, ascending.
    std::vector<int> missing() const;
    /// Joins a depth part of the current pass by its summary, in place of the part: only for a
    /// run kept for its outputs, which takes no more of it. Throws InvalidInput as add(), and
    /// when the run is not one or the summary's orientations are not the pass's.
    void add_depth_summary(const DepthPartSummary& summary);
    /// Joins the parts of the pass and moves to the next pass the mesh needs. Throws
    /// InvalidInput naming the missing tiles when some part is not in.
    void finish_pass();
    /// Joins the current texel pass from its texels (positive, negative) joined already
    /// (tile_alone.hpp's join_texels, or the file a job left of them:
    /// pipeline/joined_texels.hpp) instead of every tile's part: the same state as add() of
    /// every part and finish_pass(), without holding the parts' regions. Only for a run kept
    /// for its outputs (TiledResult::Outputs), whose merge is the one such texels come from,
    /// and which needs no texel's depth (it makes no rims part). Throws InvalidInput when the
    /// run is not one, waits for another pass or has a part of this one in already, or when a
    /// texel is not of its orientation or its faces are not the mesh's.
    void finish_texel_pass(std::array<TexelSet, 2> texels);
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
