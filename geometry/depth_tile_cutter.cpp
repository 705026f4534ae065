#include "geometry/detail/depth_tile_cutter.hpp"

#include <stdexcept>

namespace geotex::detail {

DepthTileCutter::DepthTileCutter(const Mesh& mesh)
    : mesh_(&mesh), positions_(mesh.positions), num_faces_(mesh.faces.size()) {}

DepthTileCutter::DepthTileCutter(const MeshOutline& outline)
    : positions_(outline.positions),
      num_faces_(static_cast<std::size_t>(outline.extent.num_faces)),
      blocks_(outline.blocks),
      placed_(outline.placed) {}

void DepthTileCutter::set_run(const TileBoxes& boxes, const SmoothingParams& params,
                              double radius) {
    boxes_ = boxes;
    params_ = params;
    radius_ = radius;
}

void DepthTileCutter::expect_blocks(const char* what) const {
    if (!blocks_) throw std::invalid_argument(std::string("TiledSegmentation: ") + what);
}

const WholeMeshChoices& DepthTileCutter::whole_choices() const {
    std::call_once(whole_once_, [&] {
        whole_ = blocks_ ? whole_mesh_choices(positions_, blocks_, num_faces_, params_)
                         : whole_mesh_choices(*mesh_, params_);
    });
    return whole_;
}

const int* DepthTileCutter::streamed_ids() const {
    return placed_.faces ? placed_.vertex_ids : nullptr;
}

StreamTiler& DepthTileCutter::streamed() const {
    if (!stream_tiler_ && placed_.faces)
        stream_tiler_ =
            std::make_unique<StreamTiler>(placed_.positions, placed_.faces, num_faces_, boxes_,
                                          StreamTiler::kChunkSize, streamed_ids());
    if (!stream_tiler_)
        stream_tiler_ = std::make_unique<StreamTiler>(positions_, blocks_, num_faces_, boxes_);
    return *stream_tiler_;
}

DepthTile DepthTileCutter::tile(int b, double halo) const {
    const WholeMeshChoices& choices = whole_choices();
    if (!blocks_) {
        if (mesh_ == nullptr) expect_blocks("the outline cannot read its faces' blocks");
        return make_depth_tile(*mesh_, boxes_, b, halo, radius_, choices);
    }
    return make_depth_tile(streamed().tile(b, halo), static_cast<int>(positions_.size()), boxes_, b,
                           halo, radius_, choices);
}

DepthTile DepthTileCutter::tile_of_all(int b, double halo) const {
    if (mesh_ == nullptr) expect_blocks("the outline cannot read its faces' blocks");
    const std::lock_guard<std::mutex> lock(tiler_mutex_);
    if (blocks_) return tile(b, halo);
    if (!tiler_) tiler_ = std::make_unique<MeshTiler>(*mesh_, boxes_);
    return make_depth_tile(*mesh_, boxes_, b, halo, radius_, whole_choices(), tiler_.get());
}

void DepthTileCutter::spool(
    int b, double halo, const std::string& scratch_dir,
    const std::function<void(const DepthTile& numbers, const DepthTileRows& rows)>& use) const {
    expect_blocks("spool_depth_tile needs an outline's blocks");
    const std::lock_guard<std::mutex> lock(tiler_mutex_);
    StreamTiler& tiler = streamed();
    if (!spooled_choices_)
        spooled_choices_ = std::make_unique<SpooledChoices>(
            whole_mesh_choices(positions_, blocks_, num_faces_, params_), streamed_ids(),
            positions_.size(), scratch_dir);
    const SpooledChoices& choices = *spooled_choices_;
    // The tile's numbers, with the arrays of a tile without vertices.
    const DepthTile numbers = make_depth_tile(MeshTile{}, static_cast<int>(positions_.size()),
                                              boxes_, b, halo, radius_, choices.outline());
    tiler.spool(b, halo, scratch_dir,
                [&](const SpooledTile& spooled) { use(numbers, *spooled_rows(spooled, choices)); });
}

}  // namespace geotex::detail
