#pragma once
/// Spatial tiles of a mesh (issue 21, item 3; docs/tiles.md): a mesh cut into boxes, each with
/// a halo of the faces around it, so that a scan larger than memory, or one spread over several
/// machines, is segmented a tile at a time. What a tile computes for the vertices of its box
/// equals what the whole mesh gives them when the halo is wide enough and the tile takes the
/// few choices that depend on the whole mesh from it (the fast mode's sampling, the connected
/// components): this header gives the boxes, the tiles, and the depth maps and texels made tile
/// by tile; tiled_segmentation.hpp the whole segmentation in tiles.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/depth_map.hpp"
#include "geometry/face_blocks.hpp"
#include "geometry/mesh.hpp"
#include "geometry/scratch_file.hpp"
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
    /// Box b's lowest and highest corners, as distance() finds them.
    std::pair<Eigen::Vector3d, Eigen::Vector3d> corners(int b) const;
    /// Euclidean distance from `p` to the box from `lo` to `hi` (0 inside); inline, for the
    /// tilers' loops over every vertex.
    static double distance(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                           const Eigen::Vector3d& p) {
        double squared = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const double gap = std::max({lo[axis] - p[axis], p[axis] - hi[axis], 0.0});
            squared += gap * gap;
        }
        return std::sqrt(squared);
    }
};

/// `count` boxes (>= 1) over the mesh's bounding box: its longest side cut into nx and the
/// second longest into ny parts, nx * ny = count with nx >= ny as near each other as count
/// allows (4: 2 x 2, 9: 3 x 3, 6: 3 x 2). Throws InvalidInput on a count below 1 or a mesh
/// without vertices.
TileBoxes make_tile_boxes(PositionSpan positions, int count);

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

/// Which of a mesh's vertices and faces lie in a tile's box, for make_mesh_tile when they are
/// known already: the cut of a tile knows them (MeshTile::owned_vertex and owned_face). Not
/// owned; both null: not known.
struct KnownOwned {
    const std::vector<char>* vertex = nullptr;  ///< #V: the vertex lies in the box
    const std::vector<char>* face = nullptr;    ///< #F: the face's centroid lies in the box
};

/// Tile `index` of `boxes` with a halo `halo` wide (>= 0, mesh units). Every face of the mesh
/// is owned by one tile, and every vertex of a face by one. The halo is measured in space, so
/// it holds every vertex within that geodesic distance of the box too. `known`, when given,
/// says which of the mesh's vertices and faces lie in the box, which spares finding their
/// boxes again. Each call scans the whole mesh: MeshTiler cuts many tiles of one mesh. Throws
/// InvalidInput on an index out of range, a halo that is negative or not finite, or `known` of
/// another size.
MeshTile make_mesh_tile(const Mesh& mesh, const TileBoxes& boxes, int index, double halo,
                        const KnownOwned& known = {});

/// Cuts many tiles of one mesh, each in time proportional to the faces near its box rather
/// than to the whole mesh (the repair in tiles and the mesh job of a tiled run cut every tile
/// of a scan of 84 million faces, and a scan of the whole mesh per tile was a third of the
/// mesh job's processor time). The faces are sorted once into a grid finer than the boxes; a tile
/// looks only at the cells within its halo, plus the greatest reach of a face from its centroid,
/// and decides on each of their faces as make_mesh_tile does, so each tile equals make_mesh_tile's.
/// Holds 4 bytes a face and 5 a vertex beside the mesh, which it refers to and must outlive it. Not
/// for concurrent use: the tiles share its scratch.
class MeshTiler {
  public:
    /// Throws InvalidInput when `boxes` has no box.
    MeshTiler(const Mesh& mesh, const TileBoxes& boxes);
    /// make_mesh_tile(mesh, boxes, index, halo), with its errors.
    MeshTile tile(int index, double halo);

  private:
    const Mesh& mesh_;
    TileBoxes boxes_;
    std::array<int, 3> cells_{1, 1, 1};  // the fine grid's cells along each axis
    std::vector<int> cell_offsets_;      // #cells + 1: cell c's faces in faces_
    std::vector<int> faces_;             // #F: the faces by the cell of their centroid, ascending
    double reach_ = 0;                   // greatest distance from a centroid to its corners
    double slack_ = 0;                   // more than the rounding of the cells' bounds
    std::vector<char> where_;            // #V scratch: make_mesh_tile's code, or unknown
    std::vector<int> local_;             // #V scratch: the vertex's number in the tile
    std::vector<std::uint64_t> taken_, owned_, used_;  // bit sets of faces, faces and vertices
};

class StreamTiler;

/// A block of a tile's faces, in the tile's order (SpooledTile::for_each_face_block): as
/// MeshTile holds them, over the tile's vertex numbers, with their ids in the whole mesh and
/// whether the tile owns them.
struct TileFaceBlock {
    std::vector<std::array<int, 3>> faces;  ///< #n by 3, over the tile's vertex numbers
    std::vector<int> ids;                   ///< #n: the face's id in the whole mesh, ascending
    std::vector<char> owned;                ///< #n: the face's centroid lies in the tile's box
};

/// A tile that StreamTiler::spool cut without holding it, read a value or a block at a time:
/// the MeshTile that StreamTiler::tile gives, value for value. Its faces wait in a scratch file
/// and come back a block at a time, renumbered; a vertex's position and flags are read from the
/// tiler. Valid only inside the call of spool that gives it.
class SpooledTile {
  public:
    /// #V_tile: each vertex's id in the whole mesh, ascending (MeshTile::vertex).
    const std::vector<int>& vertex() const { return vertex_; }
    std::size_t num_vertices() const { return vertex_.size(); }
    std::size_t num_faces() const { return num_faces_; }
    /// Vertex k's number in the tiler's positions: its place, for a tiler given vertex ids.
    std::size_t place(std::size_t k) const { return static_cast<std::size_t>(at_[k]); }
    /// Vertex k's position and flags (MeshTile's mesh.positions, owned_vertex, complete_vertex).
    Eigen::Vector3d position(std::size_t k) const;
    bool owned_vertex(std::size_t k) const;
    bool complete_vertex(std::size_t k) const;
    /// Calls fn(block) for the tile's faces in order, as many at a time as spool was told.
    /// Throws IoError when the scratch file cannot be read.
    void for_each_face_block(const std::function<void(const TileFaceBlock&)>& fn) const;

  private:
    friend class StreamTiler;
    explicit SpooledTile(const StreamTiler& tiler, const std::string& scratch_dir);

    const StreamTiler& tiler_;
    std::vector<int> vertex_;
    std::vector<int> at_;  // #V_tile: the vertex's number in the tiler's positions
    // Four values a face: its corners in the tiler's numbers and its id, complemented (~id)
    // when the tile does not own it.
    mutable ScratchFile faces_;
    std::size_t num_faces_ = 0;
    std::size_t block_ = kFaceBlock;
};

/// Cuts tiles of a mesh whose faces are not held but read a block at a time (face_blocks.hpp),
/// so that the mesh job of a tiled run cuts every tile of a mesh it keeps on disk holding the
/// positions, 1.2 bytes a vertex of scratch (each vertex's flags for the tile, and a bit set of
/// the tile's vertices) and the tile (spool: the numbers of the tile's vertices alone). It keeps
/// the bounds of each chunk of vertex and face ids; a tile passes over the chunks that lie farther
/// from its box than its halo (and a face's reach), and reads the faces of the others, so that on a
/// scan whose neighbours have near ids a tile reads about its own faces. Each tile equals
/// make_mesh_tile's. Refers to `positions`, which must outlive it. Not for concurrent use: the
/// tiles share its scratch.
///
/// A scan whose vertex ids do not follow space (sphere-1's) is cut with its vertices numbered
/// by their places in space (SpaceOrderedPositions: `positions` its copy(), `faces` renumbered
/// by faces_in_places, and `vertex_ids` its ids()): a chunk of places is then a piece of space,
/// which a tile passes over unless it is near, and the positions a tile reads are its own.
/// Each tile is still given in vertex ids, ascending.
class StreamTiler {
  public:
    /// Face and vertex ids to a chunk, by default.
    static constexpr std::size_t kChunkSize = std::size_t{1} << 16;

    /// `faces` reads the mesh's `num_faces` faces; one pass over them here finds each chunk's
    /// bounds (`chunk_size` ids to a chunk, at most kFaceBlock) and the greatest reach of a face
    /// from its centroid. With `vertex_ids`, `positions` and `faces` number the vertices
    /// otherwise, and vertex_ids[u] is vertex u's id in the tiles. Throws InvalidInput when
    /// `boxes` has no box, and what `faces` throws.
    StreamTiler(PositionSpan positions, FaceBlockReader faces, std::size_t num_faces,
                const TileBoxes& boxes, std::size_t chunk_size = kChunkSize,
                const int* vertex_ids = nullptr);
    /// make_mesh_tile(mesh, boxes, index, halo) of the mesh of these positions and faces, with
    /// its errors and what `faces` throws.
    MeshTile tile(int index, double halo);
    /// tile(index, halo) given to `use` as a SpooledTile rather than held, with the same
    /// errors and IoError naming `scratch_dir`, where its faces wait (16 bytes a face, in a file
    /// without a name). Holds 8 bytes a vertex of the tile (12 for a tiler given vertex ids)
    /// beside the tiler's scratch, where tile() holds the tile: 35 bytes a vertex and 17 a
    /// face (the mesh job of a tiled run writes each tile to its file, pipeline/tile_mesh.hpp,
    /// and need not hold it).
    /// Its faces come back `block` at a time (at least 1).
    void spool(int index, double halo, const std::string& scratch_dir,
               const std::function<void(const SpooledTile&)>& use, std::size_t block = kFaceBlock);

  private:
    friend class SpooledTile;
    // The vertices' flags for tile `index` (where_); gives which chunks of faces the tile reads
    // (1) or passes over (0), and `bound`, the faces of those it reads.
    std::vector<char> mark(int index, double halo, std::size_t& bound);
    // Calls take(id, face, owned) for each face the tile takes, in order, from the chunks
    // `read` marks, and sets the bits of its corners in used_.
    template <class Take>
    void take_faces(int index, const std::vector<char>& read, Take&& take);
    // Calls cut(), which takes a tile's faces and numbers its vertices, then forgets the tile
    // however cut() ends: the bits of a tile whose read of the faces failed (a full scratch
    // disk, for spool) would be counted by the next tile as its own.
    template <class Cut>
    void with_tile(Cut&& cut);
    // The tile's vertices (used_) numbered by id (local()), their ids to `ids`; gives their
    // numbers in positions_, ascending.
    std::vector<int> number_vertices(std::vector<int>& ids);
    // Vertex v's number in the tile: v must be one of its vertices (used_), numbered.
    int local(int v) const;
    // Clears the tile's vertices (used_, order_) for the next tile.
    void forget_tile();
    std::size_t block_faces() const;  // faces read at most at once: whole chunks
    void number_by_id(const std::vector<int>& cut, std::vector<int>& ids);
    bool far(const std::pair<Eigen::Vector3d, Eigen::Vector3d>& bounds, const Eigen::Vector3d& from,
             const Eigen::Vector3d& to, double reach) const;

    PositionSpan positions_;
    FaceBlockReader faces_;
    const int* vertex_ids_ = nullptr;
    std::size_t num_faces_ = 0;
    int chunk_ = 1;
    TileBoxes boxes_;
    // Each chunk's lowest and highest corners.
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> vertex_chunks_, face_chunks_;
    double reach_ = 0;         // greatest distance from a centroid to its corners
    double slack_ = 0;         // more than the rounding of a distance to a box
    std::vector<char> where_;  // #V scratch: the vertex's flags for the tile
    // The tile's vertices: a bit set over the tiler's numbers, the vertices set before each of
    // its words, and the tile's number of each (by its rank among them; none: the rank). A
    // vertex's number is so found from 0.2 bytes a vertex of the whole mesh and 4 a vertex of
    // the tile, where an array of every vertex's number would hold 4 bytes a vertex of the
    // whole mesh (168 MB at sphere-1 level 11) while the cutting reads its positions through
    // the page cache.
    std::vector<std::uint64_t> used_;
    std::vector<int> rank_;
    std::vector<int> order_;
    std::vector<std::array<int, 3>> block_;  // scratch kept between tiles: the faces read
    std::vector<char> taken_;                // and whether the tile takes each
};

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

/// The halo, in multiples of r, of the tiles that a tiled run's mesh job writes for the jobs of
/// the passes (DepthTile): the depth halo (6r), which a depth or rims job cuts from it, and
/// room for the texels that reach past their first halo (3r) to grow again around themselves,
/// so that a texel up to about 12r across is grown, and its features computed, in its tile.
/// Sphere-1's texels at 1% span up to 10.7r.
constexpr double kTileMeshHaloRadii = 12;

/// The texels of each depth map in `depth` (#V and #F of the whole mesh each, e.g. from
/// make_tiled_depth_maps) computed tile by tile: the seeds' threshold is the whole mesh's,
/// each tile grows the regions of the seeds it owns, and the regions of every tile are merged
/// as make_texels merges them. Equal to make_texels on the whole mesh, whose topology is never
/// built. `halo` is at least kTexelHaloRadii * r, which the seeds' discs want (0 takes that);
/// the seed of a region that reaches the edge
/// of its tile's halo grows again in a cut around the region, wider each time it reaches that
/// cut's edge, so a texel larger than the halo costs time, not exactness. Throws InvalidInput as
/// make_texels.
std::vector<TexelSet> make_tiled_texels(const Mesh& mesh, const std::vector<DepthMap>& depth,
                                        const TexelParams& params, int tiles, double halo = 0);

}  // namespace geotex
