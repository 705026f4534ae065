#include "geometry/tile_alone.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/segmentation_steps.hpp"
#include "geometry/detail/tile_steps.hpp"

namespace geotex {

using detail::expect_depth_part;
using detail::expect_part;
using detail::first_depth_orientations;
using detail::index_of;

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

// `tile` cut to the depth halo, the tile that TiledSegmentation's depth and rims passes cut.
DepthTile at_depth_halo(DepthTile tile) {
    const double halo = kDepthHaloRadii * tile.radius;
    if (tile.halo > halo) return detail::narrowed_depth_tile(tile, halo);
    return tile;
}

}  // namespace

TilePart first_depth_part(DepthTile tile, const SegmentationParams& params) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    tile = at_depth_halo(std::move(tile));
    const SmoothingParams sp = detail::smoothing_params(params, tile.radius);
    TilePart part =
        detail::depth_part(std::move(tile), sp, first_depth_orientations(params), {}, true);
    part.pass = TilePass::Depth;
    return part;
}

TilePass texel_pass_after(TilePass depth_pass) {
    return depth_pass == TilePass::Depth ? TilePass::Texels : TilePass::TexelsWithoutRims;
}

DepthPassOf first_depth_pass(const SegmentationParams& params) {
    return {TilePass::Depth, first_depth_orientations(params)};
}

namespace {

// Depth pass `of`'s depths at the tile's vertices, picked from the parts: from every part when
// `greatest` is given, else from those of the tiles whose boxes hold a vertex of the tile.
// `greatest` gets each orientation's greatest depth over every part and 0 (what
// set_face_depths gives the joined maps).
std::vector<std::vector<double>> picked_depths(const DepthTile& tile, const DepthPassOf& of,
                                               const TilePartSource& part_of,
                                               std::vector<double>* greatest) {
    const std::size_t n = of.orientations.size();
    const std::vector<int>& ids = tile.mesh.vertex;
    std::vector<std::vector<double>> depths(n, std::vector<double>(ids.size(), 0.0));
    if (greatest) greatest->assign(n, 0.0);
    std::vector<char> given(ids.size(), 0);
    std::size_t count = 0;
    // A vertex's depth is in the part of the tile whose box holds it: unless every part is
    // wanted, the parts of tiles holding none of this tile's vertices are not read (at 1% a
    // tile and its halo reach only the tiles around it).
    const bool all_parts = greatest != nullptr;
    std::vector<char> needed(static_cast<std::size_t>(tile.boxes.size()), all_parts ? 1 : 0);
    if (!all_parts)
        for (const Eigen::Vector3d& p : tile.mesh.mesh.positions) needed[tile.boxes.box_of(p)] = 1;
    for (int k = 0; k < tile.boxes.size(); ++k) {
        if (!needed[k]) continue;
        const TilePart part = part_of(k);
        expect_depth_part(part, of.pass, k, n, tile.mesh_vertices);
        if (greatest)
            for (std::size_t i = 0; i < n; ++i)
                for (double d : part.depths[i]) (*greatest)[i] = std::max((*greatest)[i], d);
        // Both id lists ascend: one walk over each.
        std::size_t a = 0;
        for (std::size_t j = 0; j < part.vertices.size() && a < ids.size(); ++j) {
            while (a < ids.size() && ids[a] < part.vertices[j]) ++a;
            if (a == ids.size() || ids[a] != part.vertices[j]) continue;
            expect_part(!given[a], of.pass, k,
                        "vertex " + std::to_string(ids[a]) + " has a depth in another part");
            for (std::size_t i = 0; i < n; ++i) depths[i][a] = part.depths[i][j];
            given[a] = 1;
            ++count;
        }
    }
    if (count != ids.size())
        throw InvalidInput(std::string("tiles: the parts of pass ") + name_of(of.pass) + " give " +
                           std::to_string(count) + " of the " + std::to_string(ids.size()) +
                           " vertices of tile " + std::to_string(tile.tile + 1) + " their depth");
    return depths;
}

}  // namespace

std::vector<double> texel_thresholds_merged(const DepthTile& tile, const SegmentationParams& params,
                                            const DepthPassOf& of,
                                            const SortedDepthSource& sorted_of) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    const TexelParams tp = detail::texel_params(params, tile.radius);
    const std::size_t mesh_vertices = static_cast<std::size_t>(tile.mesh_vertices);
    std::vector<double> out;
    for (std::size_t i = 0; i < of.orientations.size(); ++i) {
        std::vector<std::unique_ptr<SortedValues>> held;
        std::vector<SortedValues*> runs;
        std::size_t total = 0;
        for (int k = 0; k < tile.boxes.size(); ++k) {
            held.push_back(sorted_of(k, i));
            runs.push_back(held.back().get());
            if (runs.back()) total += runs.back()->size();
        }
        if (total > mesh_vertices)
            throw InvalidInput(std::string("tiles: the sorted depths of pass ") + name_of(of.pass) +
                               " give more depths than the mesh has vertices");
        // A vertex on no face is in no tile: its depth stays 0 in the joined map (add_depth),
        // and counts there.
        out.push_back(
            texel_global_threshold(otsu_threshold_merged(runs, mesh_vertices - total), tp));
    }
    return out;
}

std::vector<std::vector<double>> depths_in_tile(const DepthTile& tile,
                                                const SegmentationParams& params,
                                                const DepthPassOf& of,
                                                const TilePartSource& part_of) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    return picked_depths(tile, of, part_of, nullptr);
}

std::optional<TilePart> texel_part_in_tile(DepthTile tile, std::vector<std::vector<double>> depths,
                                           const std::vector<double>& thresholds,
                                           const SegmentationParams& params, const DepthPassOf& of,
                                           const std::function<Mesh()>& read_mesh_again) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    // The smoothing's choices: the depth passes' alone.
    tile.sampling = {};
    tile.components = {};
    const std::size_t n = of.orientations.size();
    bool fit = depths.size() == n && thresholds.size() == n;
    for (std::size_t i = 0; fit && i < n; ++i)
        // +inf where Otsu finds no split (a mesh without detail): no seed, as in the whole run.
        fit = depths[i].size() == tile.mesh.vertex.size() && thresholds[i] >= 0;
    if (!fit)
        throw InvalidInput("tiles: tile " + std::to_string(tile.tile + 1) +
                           ": the depths or thresholds do not fit its vertices and the pass");
    // The tile's own depth maps, of vertex depths alone: each cut of the tile the regions
    // grow in makes its faces' depths from its vertices' as the joined maps make them
    // (set_face_depths), so the same bits, and the tile's are never held beside a cut's.
    std::vector<DepthMap> maps(n);
    std::vector<const DepthMap*> maps_of;
    for (std::size_t i = 0; i < n; ++i) {
        maps[i].orientation = of.orientations[i];
        maps[i].vertex_depth = std::move(depths[i]);
        maps_of.push_back(&maps[i]);
    }
    std::optional<TilePart> part = detail::texel_part(
        tile.mesh.mesh, maps_of, thresholds, detail::texel_params(params, tile.radius), tile.boxes,
        tile.tile, kTexelHaloRadii * tile.radius, tile.halo, &tile.mesh, read_mesh_again);
    if (!part) return std::nullopt;
    detail::renumber_regions(part->regions, tile.mesh.vertex, tile.mesh.face);  // the whole mesh's
    part->pass = texel_pass_after(of.pass);
    return part;
}

JoinedTexels join_texels(const DepthTile& tile, const SegmentationParams& params,
                         const DepthPassOf& of, const TilePartSource& part_of) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    const std::vector<DetailOrientation>& orientations = of.orientations;
    const TilePass pass = texel_pass_after(of.pass);
    const std::size_t n = orientations.size();
    std::vector<detail::TexelRegionJoin> all(n);
    std::vector<double> thresholds;
    for (int k = 0; k < tile.boxes.size(); ++k) {
        TilePart part = part_of(k);
        // The faces' ids are checked to ascend; their bound, #F, is not in a tile.
        detail::expect_texel_part(part, pass, k, n, tile.mesh_vertices,
                                  std::numeric_limits<int>::max());
        if (k == 0) thresholds = part.thresholds;
        expect_part(part.thresholds == thresholds, pass, k,
                    "its seed thresholds are not those of tile 1's part");
        for (std::size_t i = 0; i < n; ++i)
            all[i].add(std::move(part.regions[i]), std::move(part.region_depths[i]));
    }
    const TexelParams tp = detail::texel_params(params, tile.radius);
    JoinedTexels out;
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t o = index_of(orientations[i]);
        out.texels[o] = all[i].merge(tp, orientations[i], thresholds[i], out.depth[o]);
    }
    return out;
}

namespace {

// The texels each run's second smoothing leaves out, from every part's flags or-ed.
JoinedRims rims_of(const RimFlags& flags, const SegmentationParams& params) {
    JoinedRims out;
    out.second.pass = TilePass::DepthWithoutRims;
    std::vector<int> counts;
    out.use = detail::rim_exclusions(flags, detail::orientations_of(params.orientation), counts,
                                     out.second.orientations);
    return out;
}

}  // namespace

JoinedRims join_rims(const DepthTile& tile, const JoinedTexels& texels,
                     const SegmentationParams& params, const TilePartSource& part_of) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    RimFlags flags = no_rim_flags(texels.texels[0].texels.size(), texels.texels[1].texels.size());
    for (int k = 0; k < tile.boxes.size(); ++k) detail::add_rim_part(part_of(k), k, flags);
    return rims_of(flags, params);
}

JoinedRims join_rims_alone(int tiles, const SegmentationParams& params,
                           const TilePartSource& part_of) {
    check_segmentation_params(params);
    if (tiles < 1) throw InvalidInput("tiles: the rims of a run of no tile");
    const TilePart first = part_of(0);
    RimFlags flags = no_rim_flags(first.rims.positive_rim.size(), first.rims.negative_rim.size());
    detail::add_rim_part(first, 0, flags);
    for (int k = 1; k < tiles; ++k) detail::add_rim_part(part_of(k), k, flags);
    return rims_of(flags, params);
}

TilePart depth_without_rims_part(DepthTile tile, const JoinedTexels& texels, const JoinedRims& rims,
                                 const SegmentationParams& params) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    bool fit = rims.second.pass == TilePass::DepthWithoutRims && !rims.second.orientations.empty();
    for (DetailOrientation o : rims.second.orientations)
        fit = fit && rims.use[index_of(o)].size() == texels.texels[1 - index_of(o)].texels.size();
    if (!fit)
        throw InvalidInput(
            "tiles: the joined rims do not fit the texels, or leave nothing out of a second "
            "smoothing");
    tile = at_depth_halo(std::move(tile));
    const SmoothingParams sp = detail::smoothing_params(params, tile.radius);
    TilePart part =
        detail::depth_part(std::move(tile), sp, rims.second.orientations,
                           detail::rim_exclusion({&texels.texels[0], &texels.texels[1]}, rims.use,
                                                 detail::rim_params(sp.radius)),
                           false);
    part.pass = TilePass::DepthWithoutRims;
    return part;
}

std::vector<Texel> segmentation_texels(JoinedTexels first, JoinedTexels second,
                                       const JoinedRims& rims, const SegmentationParams& params) {
    check_segmentation_params(params);
    std::vector<Texel> out;
    std::vector<int> used;  // the faces of the texels kept from the orientations before
    for (DetailOrientation o : detail::orientations_of(params.orientation)) {
        const std::vector<DetailOrientation>& again = rims.second.orientations;
        const bool smoothed_again = std::find(again.begin(), again.end(), o) != again.end();
        TexelSet& set = (smoothed_again ? second : first).texels[index_of(o)];
        std::vector<int> taken;
        for (Texel& t : set.texels) {
            // The texels of one orientation share no face: only those of the orientations
            // before take one (collect_texels).
            t.faces.erase(std::remove_if(t.faces.begin(), t.faces.end(),
                                         [&](int f) {
                                             return std::binary_search(used.begin(), used.end(), f);
                                         }),
                          t.faces.end());
            if (static_cast<int>(t.faces.size()) < params.min_faces) continue;
            taken.insert(taken.end(), t.faces.begin(), t.faces.end());
            out.push_back(std::move(t));
        }
        used.insert(used.end(), taken.begin(), taken.end());
        std::sort(used.begin(), used.end());
    }
    return out;
}

std::optional<TilePart> features_part(DepthTile tile, const std::vector<Texel>& texels,
                                      const std::array<DepthSource, 2>& depths,
                                      const SegmentationParams& params) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    const MeshTile& m = tile.mesh;
    // The texels whose first face the tile owns, and how far they reach from its box.
    std::vector<int> ids;
    double reach = 0;
    for (std::size_t t = 0; t < texels.size(); ++t) {
        if (texels[t].faces.empty())
            throw InvalidInput("tiles: texel " + std::to_string(t + 1) + " has no face");
        const int first = detail::index_in(m.face, texels[t].faces.front());
        if (first < 0 || !m.owned_face[first]) continue;
        ids.push_back(static_cast<int>(t));
        for (int f : texels[t].faces) {
            const int g = detail::index_in(m.face, f);
            if (g < 0) return std::nullopt;  // the texel leaves the tile
            for (int v : m.mesh.faces[g])
                reach = std::max(reach, tile.boxes.distance(tile.tile, m.mesh.positions[v]));
        }
    }
    TilePart part;
    part.pass = TilePass::Features;
    part.tile = tile.tile;
    if (ids.empty()) return part;
    // The halo of TiledSegmentation's features pass.
    const double rho = params.curvature_scale * tile.radius;
    const double width = std::max(kDepthHaloRadii * tile.radius, (reach + rho) * (1 + 1e-9));
    if (width > tile.halo) return std::nullopt;
    const DepthTile cut = detail::narrowed_depth_tile(tile, width);
    // The tile as read (a 12r halo) is not held beside its cut: the features are measured in
    // the cut alone.
    tile.mesh = MeshTile();
    tile.sampling = DiscSampling();
    tile.components = VertexComponents();
    // Each depth pass's parts are read once, though both orientations may come from one pass.
    struct Read {
        const DepthPassOf* pass;
        std::vector<std::vector<double>> depths;
        std::vector<double> greatest;
    };
    std::vector<Read> read;
    std::array<std::optional<DepthMap>, 2> maps;
    for (DetailOrientation o : detail::orientations_of(params.orientation)) {
        const DepthSource& source = depths[index_of(o)];
        const std::vector<DetailOrientation>& in_pass = source.pass.orientations;
        const auto at = std::find(in_pass.begin(), in_pass.end(), o);
        if (at == in_pass.end())
            throw InvalidInput(std::string("tiles: the depths of the ") + name_of(o) +
                               " details are not in the pass given for them");
        const std::size_t i = static_cast<std::size_t>(at - in_pass.begin());
        auto r = std::find_if(read.begin(), read.end(), [&](const Read& x) {
            return x.pass->pass == source.pass.pass && x.pass->orientations == in_pass;
        });
        if (r == read.end()) {
            Read made{&source.pass, {}, source.greatest};
            if (!made.greatest.empty() && made.greatest.size() != in_pass.size())
                throw InvalidInput(std::string("tiles: the greatest depths given for pass ") +
                                   name_of(source.pass.pass) + " are not one per orientation");
            made.depths = picked_depths(cut, source.pass, source.part_of,
                                        made.greatest.empty() ? &made.greatest : nullptr);
            read.push_back(std::move(made));
            r = read.end() - 1;
        }
        DepthMap& d = maps[index_of(o)].emplace();
        d.orientation = o;
        d.vertex_depth = std::move(r->depths[i]);
        set_face_depths(cut.mesh.mesh, d);
        d.max_depth = r->greatest[i];
    }
    read.clear();  // the depths of orientations the run does not have
    TilePart made = detail::feature_part(cut.mesh, texels, ids, maps[0] ? &*maps[0] : nullptr,
                                         maps[1] ? &*maps[1] : nullptr,
                                         (tile.boxes.hi - tile.boxes.lo).maxCoeff(), rho);
    made.pass = TilePass::Features;
    made.tile = tile.tile;
    return made;
}

bool rims_needed(const JoinedTexels& texels, const SegmentationParams& params) {
    // With one orientation empty no texel can be the other's rim (make_rims).
    return params.remove_rims && !texels.texels[0].texels.empty() &&
           !texels.texels[1].texels.empty();
}

TilePart rims_part(DepthTile tile, const JoinedTexels& texels, const SegmentationParams& params) {
    check_segmentation_params(params);
    check_depth_tile(tile);
    for (std::size_t o = 0; o < 2; ++o)
        if (texels.depth[o].size() != texels.texels[o].texels.size())
            throw InvalidInput("tiles: the joined texels' depths do not match the texels");
    tile = at_depth_halo(std::move(tile));  // the rims walk within the depth halo
    TilePart part;
    part.pass = TilePass::Rims;
    part.tile = tile.tile;
    part.rims =
        detail::rim_part(tile.mesh, {&texels.texels[0], &texels.texels[1]},
                         {&texels.depth[0], &texels.depth[1]}, detail::rim_params(tile.radius));
    return part;
}

}  // namespace geotex
