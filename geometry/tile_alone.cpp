#include "geometry/tile_alone.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/segmentation_steps.hpp"
#include "geometry/detail/tile_steps.hpp"

namespace geotex {

using detail::expect_depth_part;
using detail::expect_part;
using detail::first_depth_orientations;

namespace {

// Throws InvalidInput unless `tile` is whole: its ids, flags, sampling and components fit its
// vertices and faces, and its numbers fit a run.
void check_depth_tile(const DepthTile& tile) {
    const MeshTile& m = tile.mesh;
    const std::size_t nv = m.mesh.positions.size();
    const auto fail = [&](const std::string& what) {
        throw InvalidInput("tiles: tile " + std::to_string(tile.tile + 1) +
                           "'s mesh is not whole: " + what);
    };
    if (tile.tile < 0 || tile.tile >= tile.boxes.size() || tile.boxes.size() < 1)
        fail("its number is not one of the run's tiles");
    if (!(tile.radius > 0) || !std::isfinite(tile.radius)) fail("its radius is not positive");
    if (!(tile.halo >= kDepthHaloRadii * tile.radius) || !std::isfinite(tile.halo))
        fail("its halo is narrower than the depth maps need");
    if (m.vertex.size() != nv || m.owned_vertex.size() != nv || m.complete_vertex.size() != nv ||
        m.face.size() != m.mesh.faces.size() || m.owned_face.size() != m.mesh.faces.size())
        fail("its ids and flags do not match its vertices and faces");
    if (!detail::ascending_ids(m.vertex, tile.mesh_vertices))
        fail("its vertex ids are not ascending ids of the mesh's vertices");
    if (tile.sampling.fast.size() != nv || tile.components.component.size() != nv)
        fail("its sampling or components do not match its vertices");
    for (int c : tile.components.component)
        if (c < 0 || c >= tile.components.num_components) fail("a component is out of range");
}

}  // namespace

TilePart first_depth_part(DepthTile tile, const SegmentationParams& params) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    const double halo = kDepthHaloRadii * tile.radius;
    if (tile.halo > halo) tile = detail::narrowed_depth_tile(tile, halo);
    const SmoothingParams sp = detail::smoothing_params(params, tile.radius);
    TilePart part =
        detail::depth_part(std::move(tile), sp, first_depth_orientations(params), {}, true);
    part.pass = TilePass::Depth;
    return part;
}

std::vector<double> first_texel_thresholds(const DepthTile& tile, const SegmentationParams& params,
                                           const TilePartSource& part_of) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    const std::size_t n = first_depth_orientations(params).size();
    const TexelParams tp = detail::texel_params(params, tile.radius);
    std::vector<double> thresholds;
    for (std::size_t i = 0; i < n; ++i) {
        std::vector<double> all;
        all.reserve(static_cast<std::size_t>(tile.mesh_vertices));
        for (int k = 0; k < tile.boxes.size(); ++k) {
            const TilePart part = part_of(k);
            expect_depth_part(part, TilePass::Depth, k, n, tile.mesh_vertices);
            all.insert(all.end(), part.depths[i].begin(), part.depths[i].end());
        }
        // A vertex on no face is in no tile: its depth stays 0 in the joined map (add_depth),
        // and counts there. Otsu sorts, so where its zero goes in `all` does not matter.
        if (all.size() > static_cast<std::size_t>(tile.mesh_vertices))
            throw InvalidInput(
                "tiles: the parts of pass depth give more depths than the mesh "
                "has vertices");
        all.resize(static_cast<std::size_t>(tile.mesh_vertices), 0.0);
        thresholds.push_back(texel_global_threshold(std::move(all), tp));
    }
    return thresholds;
}

std::vector<std::vector<double>> first_depths_in_tile(const DepthTile& tile,
                                                      const SegmentationParams& params,
                                                      const TilePartSource& part_of) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    const std::size_t n = first_depth_orientations(params).size();
    const std::vector<int>& ids = tile.mesh.vertex;
    std::vector<std::vector<double>> depths(n, std::vector<double>(ids.size(), 0.0));
    std::vector<char> given(ids.size(), 0);
    std::size_t count = 0;
    for (int k = 0; k < tile.boxes.size(); ++k) {
        const TilePart part = part_of(k);
        expect_depth_part(part, TilePass::Depth, k, n, tile.mesh_vertices);
        // Both id lists ascend: one walk over each.
        std::size_t a = 0;
        for (std::size_t j = 0; j < part.vertices.size() && a < ids.size(); ++j) {
            while (a < ids.size() && ids[a] < part.vertices[j]) ++a;
            if (a == ids.size() || ids[a] != part.vertices[j]) continue;
            expect_part(!given[a], TilePass::Depth, k,
                        "vertex " + std::to_string(ids[a]) + " has a depth in another part");
            for (std::size_t i = 0; i < n; ++i) depths[i][a] = part.depths[i][j];
            given[a] = 1;
            ++count;
        }
    }
    if (count != ids.size())
        throw InvalidInput("tiles: the parts of pass depth give " + std::to_string(count) +
                           " of the " + std::to_string(ids.size()) + " vertices of tile " +
                           std::to_string(tile.tile + 1) + " their depth");
    return depths;
}

std::optional<TilePart> first_texel_part(const DepthTile& tile,
                                         const std::vector<std::vector<double>>& depths,
                                         const std::vector<double>& thresholds,
                                         const SegmentationParams& params) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    const std::vector<DetailOrientation> orientations = first_depth_orientations(params);
    const std::size_t n = orientations.size();
    bool fit = depths.size() == n && thresholds.size() == n;
    for (std::size_t i = 0; fit && i < n; ++i)
        fit = depths[i].size() == tile.mesh.vertex.size() && std::isfinite(thresholds[i]);
    if (!fit)
        throw InvalidInput("tiles: tile " + std::to_string(tile.tile + 1) +
                           ": the depths or thresholds do not fit its vertices and the pass");
    // The tile's own depth maps: the faces' depths from its vertices', as the joined maps
    // make them (set_face_depths), so the same bits.
    std::vector<DepthMap> maps(n);
    std::vector<const DepthMap*> of;
    for (std::size_t i = 0; i < n; ++i) {
        maps[i].orientation = orientations[i];
        maps[i].vertex_depth = depths[i];
        set_face_depths(tile.mesh.mesh, maps[i]);
        of.push_back(&maps[i]);
    }
    std::optional<std::vector<TexelRegions>> regions = detail::texel_part(
        tile.mesh.mesh, of, thresholds, detail::texel_params(params, tile.radius), tile.boxes,
        tile.tile, kTexelHaloRadii * tile.radius, tile.halo);
    if (!regions) return std::nullopt;
    detail::renumber_regions(*regions, tile.mesh.vertex, tile.mesh.face);  // the whole mesh's ids
    TilePart part;
    part.pass = TilePass::Texels;
    part.tile = tile.tile;
    part.regions = std::move(*regions);
    return part;
}

}  // namespace geotex
