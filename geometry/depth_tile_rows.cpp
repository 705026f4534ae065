// The rows through which a tile mesh file is written (DepthTileRows), over a tile held in
// memory or one that a StreamTiler spools: two views of the same values, kept apart from the
// cutting of the tiles (depth_tile_cutter.cpp), which only hands a spooled tile's rows on.
#include <functional>
#include <memory>

#include "geometry/detail/tile_steps.hpp"
#include "geometry/tiled_segmentation.hpp"

namespace geotex {

namespace {

// The rows of a tile that a StreamTiler spools, with the whole mesh's choices at its vertices.
class SpooledDepthTileRows final : public DepthTileRows {
  public:
    SpooledDepthTileRows(const SpooledTile& tile, const detail::SpooledChoices& choices)
        : tile_(tile), choices_(choices) {}
    std::size_t num_vertices() const override { return tile_.num_vertices(); }
    std::size_t num_faces() const override { return tile_.num_faces(); }
    Eigen::Vector3d position(std::size_t k) const override { return tile_.position(k); }
    int vertex_id(std::size_t k) const override { return tile_.vertex()[k]; }
    bool owned_vertex(std::size_t k) const override { return tile_.owned_vertex(k); }
    bool complete_vertex(std::size_t k) const override { return tile_.complete_vertex(k); }
    bool fast(std::size_t k) const override { return choices_.fast(tile_.place(k)); }
    int component(std::size_t k) const override { return choices_.component(tile_.place(k)); }
    void for_each_face_block(const std::function<void(const TileFaceBlock&)>& fn) const override {
        tile_.for_each_face_block(fn);
    }

  private:
    const SpooledTile& tile_;
    const detail::SpooledChoices& choices_;
};

// The rows of a held tile.
class HeldDepthTileRows final : public DepthTileRows {
  public:
    explicit HeldDepthTileRows(const DepthTile& tile) : tile_(tile) {}
    std::size_t num_vertices() const override { return tile_.mesh.vertex.size(); }
    std::size_t num_faces() const override { return tile_.mesh.face.size(); }
    Eigen::Vector3d position(std::size_t k) const override { return tile_.mesh.mesh.positions[k]; }
    int vertex_id(std::size_t k) const override { return tile_.mesh.vertex[k]; }
    bool owned_vertex(std::size_t k) const override { return tile_.mesh.owned_vertex[k] != 0; }
    bool complete_vertex(std::size_t k) const override {
        return tile_.mesh.complete_vertex[k] != 0;
    }
    bool fast(std::size_t k) const override { return tile_.sampling.fast[k] != 0; }
    int component(std::size_t k) const override { return tile_.components.component[k]; }
    // The whole tile as one block: copied, since a block owns its arrays; held_rows is for the
    // tiles that are small enough to be held anyway.
    void for_each_face_block(const std::function<void(const TileFaceBlock&)>& fn) const override {
        fn({tile_.mesh.mesh.faces, tile_.mesh.face, tile_.mesh.owned_face});
    }

  private:
    const DepthTile& tile_;
};

}  // namespace

std::unique_ptr<DepthTileRows> held_rows(const DepthTile& tile) {
    return std::make_unique<HeldDepthTileRows>(tile);
}

namespace detail {

std::unique_ptr<DepthTileRows> spooled_rows(const SpooledTile& tile,
                                            const SpooledChoices& choices) {
    return std::make_unique<SpooledDepthTileRows>(tile, choices);
}

}  // namespace detail
}  // namespace geotex
