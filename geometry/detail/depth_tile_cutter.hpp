#pragma once
// How a tiled run cuts its depth tiles from the whole mesh (geometry/depth_tile_cutter.cpp):
// each tile with its halo and the whole mesh's choices at its vertices, from a held mesh or
// from an outline whose faces are read a block at a time, held or spooled. Kept apart from the
// passes of TiledSegmentation, which ask it for their tiles.

#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "geometry/detail/tile_steps.hpp"
#include "geometry/tiled_segmentation.hpp"

namespace geotex::detail {

/// The depth tiles of one mesh, cut for one run's boxes and smoothing. The whole mesh's
/// choices are found by the first tile that needs them, the tilers made by the first tile
/// they cut; the jobs of the passes after the first never need them.
class DepthTileCutter {
  public:
    /// Cuts tiles of `mesh`, which must outlive the cutter.
    explicit DepthTileCutter(const Mesh& mesh);
    /// Cuts tiles of the mesh `outline` outlines, from its blocks (MeshOutline::blocks), and
    /// in the order of space when it has them (MeshOutline::placed); what they read must
    /// outlive the cutter. Without blocks it cuts nothing (std::invalid_argument).
    explicit DepthTileCutter(const MeshOutline& outline);

    /// The boxes, the smoothing and r of the run; before the first tile.
    void set_run(const TileBoxes& boxes, const SmoothingParams& params, double radius);

    /// Tile `b` with a halo `halo` wide: make_mesh_tile's of a held mesh (several at once,
    /// from several threads), or cut from the outline's blocks.
    DepthTile tile(int b, double halo) const;
    /// The same, a held mesh's cut by a MeshTiler made by the first call and kept, for a job
    /// that cuts every tile; one call at a time.
    DepthTile tile_of_all(int b, double halo) const;
    /// TiledSegmentation::spool_depth_tile: the tile given to `use` without being held, its
    /// faces waiting in a scratch file in `scratch_dir` and the choices at its vertices read
    /// from another (SpooledChoices), made by the first call. Only from an outline's blocks.
    void spool(
        int b, double halo, const std::string& scratch_dir,
        const std::function<void(const DepthTile& numbers, const DepthTileRows& rows)>& use) const;

  private:
    // The whole mesh's choices, made once.
    const WholeMeshChoices& whole_choices() const;
    // The tiler of an outline's blocks, made by its first tile.
    StreamTiler& streamed() const;
    // The vertex ids of the stream tiler's numbers, null when they are the ids themselves.
    const int* streamed_ids() const;
    void expect_blocks(const char* what) const;

    const Mesh* mesh_ = nullptr;  // null with a MeshOutline
    PositionSpan positions_;
    std::size_t num_faces_ = 0;
    FaceBlockReader blocks_;
    MeshOutline::Placed placed_;
    TileBoxes boxes_;
    SmoothingParams params_;
    double radius_ = 0;

    mutable std::once_flag whole_once_;
    mutable WholeMeshChoices whole_;
    // The tilers' scratch is shared, so their tiles are cut one at a time.
    mutable std::mutex tiler_mutex_;
    mutable std::unique_ptr<MeshTiler> tiler_;
    mutable std::unique_ptr<StreamTiler> stream_tiler_;
    // Numbered as stream_tiler_ numbers the vertices: the mesh job reads them from a scratch
    // file rather than hold whole_.
    mutable std::unique_ptr<SpooledChoices> spooled_choices_;
};

}  // namespace geotex::detail
