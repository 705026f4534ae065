#include "geometry/tiles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/curvature.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/segmentation_steps.hpp"
#include "geometry/disc_means.hpp"
#include "geometry/feature_table.hpp"
#include "geometry/rims.hpp"
#include "geometry/topology.hpp"
#include "geometry/unit_frame.hpp"

namespace geotex {

namespace {

// Cell index of coordinate x along an axis cut into n parts from lo to hi, clamped so that the
// mesh's own extremes fall into the first and last part.
int cell_of(double x, double lo, double hi, int n) {
    if (n == 1 || !(hi > lo)) return 0;
    const double k = std::floor((x - lo) / (hi - lo) * n);
    return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
}

// The values of `whole` (one per vertex or face of the whole mesh) at the ids in `ids`.
template <class T>
std::vector<T> restricted(const std::vector<T>& whole, const std::vector<int>& ids) {
    std::vector<T> out(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) out[i] = whole[static_cast<std::size_t>(ids[i])];
    return out;
}

}  // namespace

int TileBoxes::box_of(const Eigen::Vector3d& p) const {
    const int x = cell_of(p.x(), lo.x(), hi.x(), count[0]);
    const int y = cell_of(p.y(), lo.y(), hi.y(), count[1]);
    const int z = cell_of(p.z(), lo.z(), hi.z(), count[2]);
    return (z * count[1] + y) * count[0] + x;
}

double TileBoxes::distance(int b, const Eigen::Vector3d& p) const {
    const int cell[3] = {b % count[0], (b / count[0]) % count[1], b / (count[0] * count[1])};
    double squared = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const double width = (hi[axis] - lo[axis]) / count[axis];
        const double from = lo[axis] + cell[axis] * width, to = from + width;
        const double gap = std::max({from - p[axis], p[axis] - to, 0.0});
        squared += gap * gap;
    }
    return std::sqrt(squared);
}

TileBoxes make_tile_boxes(const Mesh& mesh, int count) {
    if (count < 1)
        throw InvalidInput("tiles: the number of tiles must be at least 1 (got " +
                           std::to_string(count) + ")");
    if (mesh.positions.empty()) throw InvalidInput("tiles: the mesh has no vertex");
    TileBoxes boxes;
    boxes.lo = boxes.hi = mesh.positions.front();
    for (const auto& p : mesh.positions) {
        boxes.lo = boxes.lo.cwiseMin(p);
        boxes.hi = boxes.hi.cwiseMax(p);
    }
    // The largest factor of count not above its square root cuts the second longest side.
    int ny = 1;
    for (int k = 1; k * k <= count; ++k)
        if (count % k == 0) ny = k;
    std::array<int, 3> axes{0, 1, 2};
    const Eigen::Vector3d side = boxes.hi - boxes.lo;
    std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return side[a] > side[b]; });
    boxes.count[axes[0]] = count / ny;
    boxes.count[axes[1]] = ny;
    return boxes;
}

MeshTile make_mesh_tile(const Mesh& mesh, const TileBoxes& boxes, int index, double halo) {
    if (index < 0 || index >= boxes.size())
        throw InvalidInput("tiles: tile " + std::to_string(index) + " is not in [0, " +
                           std::to_string(boxes.size()) + ")");
    if (!(halo >= 0) || !std::isfinite(halo))
        throw InvalidInput("tiles: the halo must be >= 0 and finite");
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    // 1: the vertex is in the box, 2: within the halo of it, 0: neither.
    std::vector<char> where(static_cast<std::size_t>(nv), 0);
    detail::parallel_for(nv, [&](int v) {
        const Eigen::Vector3d& p = mesh.positions[v];
        where[v] = boxes.box_of(p) == index ? 1 : boxes.distance(index, p) <= halo ? 2 : 0;
    });
    MeshTile tile;
    std::vector<char> owned_faces;
    for (int f = 0; f < nf; ++f) {
        const auto& fv = mesh.faces[f];
        const Eigen::Vector3d centroid =
            (mesh.positions[fv[0]] + mesh.positions[fv[1]] + mesh.positions[fv[2]]) / 3.0;
        const bool owned = boxes.box_of(centroid) == index;
        if (owned || where[fv[0]] || where[fv[1]] || where[fv[2]]) {
            tile.face.push_back(f);
            tile.owned_face.push_back(owned ? 1 : 0);
        }
    }
    // The tile's vertices in the whole mesh's order, and each one's number in the tile.
    std::vector<int> local(static_cast<std::size_t>(nv), -1);
    for (int f : tile.face)
        for (int v : mesh.faces[f]) local[v] = 0;
    for (int v = 0; v < nv; ++v)
        if (local[v] == 0) {
            local[v] = static_cast<int>(tile.vertex.size());
            tile.vertex.push_back(v);
        }
    tile.mesh.positions = restricted(mesh.positions, tile.vertex);
    tile.owned_vertex.resize(tile.vertex.size());
    tile.complete_vertex.resize(tile.vertex.size());
    for (std::size_t i = 0; i < tile.vertex.size(); ++i) {
        tile.owned_vertex[i] = where[tile.vertex[i]] == 1 ? 1 : 0;
        tile.complete_vertex[i] = where[tile.vertex[i]] != 0 ? 1 : 0;
    }
    tile.mesh.faces.reserve(tile.face.size());
    for (int f : tile.face) {
        const auto& fv = mesh.faces[f];
        tile.mesh.faces.push_back({local[fv[0]], local[fv[1]], local[fv[2]]});
    }
    return tile;
}

namespace {

// What the tile passes take from the whole mesh: which discs are sampled, where the sampling
// grid starts, and which vertices are one connected piece.
struct WholeMeshChoices {
    DiscSampling sampling;
    VertexComponents components;
};

WholeMeshChoices whole_mesh_choices(const Mesh& mesh, const SmoothingParams& params) {
    DiscMeanParams disc;
    disc.radius = params.radius;
    disc.mode = params.disc;
    return {make_disc_sampling(mesh, disc), vertex_components(mesh)};
}

// The vertices a tile leaves out of its smoothing of one orientation (#V_tile; empty: none).
using TileExclusion =
    std::function<std::vector<char>(const MeshTile&, const MeshTopology&, DetailOrientation)>;

// The fast mode's counts over the whole mesh, summed over the vertices each tile owns.
struct DiscCounts {
    int interpolated = 0;
    int samples = 0;
};

// make_tiled_depth_maps, with the vertices `exclude` gives left out of each orientation's
// smoothing when it is set (the second smoothing of the rim removal); `counts`, when given,
// gets the fast mode's counts.
std::vector<DepthMap> tiled_depth_maps(const Mesh& mesh, const SmoothingParams& params,
                                       const std::vector<DetailOrientation>& orientations,
                                       const TileBoxes& boxes, double halo,
                                       const WholeMeshChoices& whole,
                                       const TileExclusion& exclude = {},
                                       DiscCounts* counts = nullptr) {
    const int nv = mesh.num_vertices();
    std::vector<DepthMap> maps(orientations.size());
    for (std::size_t i = 0; i < maps.size(); ++i) {
        maps[i].orientation = orientations[i];
        maps[i].vertex_depth.assign(static_cast<std::size_t>(nv), 0.0);
    }
    for (int b = 0; b < boxes.size(); ++b) {
        const MeshTile tile = make_mesh_tile(mesh, boxes, b, halo);
        if (tile.mesh.faces.empty()) continue;
        const MeshTopology topology = make_topology(tile.mesh);
        const MeshMetrics metrics = make_mesh_metrics(tile.mesh, topology);
        DiscSampling sampling{restricted(whole.sampling.fast, tile.vertex), whole.sampling.origin,
                              whole.sampling.grid};
        SmoothingParams sp = params;
        sp.sampling = &sampling;
        const SurfaceSmoother smoother(tile.mesh, topology, metrics, sp);
        if (counts) {
            const DiscAverager& averager = smoother.averager();
            for (std::size_t v = 0; v < tile.vertex.size(); ++v)
                if (tile.owned_vertex[v] && averager.interpolated(static_cast<int>(v)))
                    ++counts->interpolated;
            for (int v : averager.sample_vertices()) counts->samples += tile.owned_vertex[v];
        }
        std::optional<SmoothedSurface> shared;
        if (!exclude) shared = smoother.smooth();
        const DepthMapper mapper(tile.mesh, {restricted(whole.components.component, tile.vertex),
                                             whole.components.num_components});
        for (std::size_t i = 0; i < maps.size(); ++i) {
            std::optional<SmoothedSurface> own;
            if (!shared) own = smoother.smooth(exclude(tile, topology, orientations[i]));
            const SmoothedSurface& smoothed = shared ? *shared : *own;
            const DepthMap d = mapper.map(metrics.vertex_normal, smoothed, orientations[i]);
            for (std::size_t v = 0; v < tile.vertex.size(); ++v) {
                if (!tile.owned_vertex[v]) continue;
                maps[i].vertex_depth[tile.vertex[v]] = d.vertex_depth[v];
                if (stands_out(tile.mesh.positions[v], smoothed.positions[v],
                               metrics.vertex_normal[v], orientations[i]))
                    ++maps[i].num_moved_vertices;
            }
        }
    }
    for (DepthMap& d : maps) set_face_depths(mesh, d);
    return maps;
}

}  // namespace

std::vector<DepthMap> make_tiled_depth_maps(const Mesh& mesh, const SmoothingParams& params,
                                            const std::vector<DetailOrientation>& orientations,
                                            int tiles, double halo) {
    if (!(halo >= 0) || !std::isfinite(halo))
        throw InvalidInput("tiles: the halo must be >= 0 and finite");
    const TileBoxes boxes = make_tile_boxes(mesh, tiles);
    return tiled_depth_maps(mesh, params, orientations, boxes,
                            halo > 0 ? halo : kDepthHaloRadii * params.radius,
                            whole_mesh_choices(mesh, params));
}

namespace {

// make_tiled_texels over the depth maps `depth` points to, with the boxes made.
std::vector<TexelSet> tiled_texels(const Mesh& mesh, const std::vector<const DepthMap*>& depth,
                                   const TexelParams& params, const TileBoxes& boxes,
                                   double width) {
    for (const DepthMap* d : depth)
        if (d->vertex_depth.size() != mesh.positions.size() ||
            d->face_depth.size() != mesh.faces.size())
            throw InvalidInput("tiles: a depth map does not match the mesh");
    std::vector<double> thresholds;
    for (const DepthMap* d : depth)
        thresholds.push_back(texel_global_threshold(d->vertex_depth, params));

    std::vector<TexelRegions> all(depth.size());
    for (int b = 0; b < boxes.size(); ++b) {
        // A region that grows onto a face whose neighbours the tile may not all hold could
        // have grown further in the whole mesh: the tile is made again with twice the halo
        // until none does (at worst it holds the whole mesh, where every region is whole).
        std::vector<TexelRegions> grown(depth.size());
        MeshTile tile;
        for (double w = width;; w *= 2) {
            tile = make_mesh_tile(mesh, boxes, b, w);
            if (tile.mesh.faces.empty()) break;
            const MeshTopology topology = make_topology(tile.mesh);
            bool whole = true;
            for (std::size_t i = 0; i < depth.size() && whole; ++i) {
                DepthMap local;
                local.orientation = depth[i]->orientation;
                local.vertex_depth = restricted(depth[i]->vertex_depth, tile.vertex);
                local.face_depth = restricted(depth[i]->face_depth, tile.face);
                grown[i] = grow_texel_regions(tile.mesh, topology, local, params, thresholds[i],
                                              tile.owned_vertex);
                for (const TexelRegion& r : grown[i].regions)
                    for (int f : r.faces)
                        for (int v : tile.mesh.faces[f]) whole = whole && tile.complete_vertex[v];
            }
            if (whole) break;
        }
        for (std::size_t i = 0; i < depth.size(); ++i) {
            for (TexelRegion& r : grown[i].regions) {
                r.seed = tile.vertex[r.seed];
                for (int& f : r.faces) f = tile.face[f];
                for (int& f : r.touch) f = tile.face[f];
                all[i].regions.push_back(std::move(r));
            }
            all[i].num_seeds += grown[i].num_seeds;
        }
    }
    std::vector<TexelSet> out;
    for (std::size_t i = 0; i < depth.size(); ++i) {
        // The order of make_texels: deepest seed first, the lower vertex id on a tie.
        const std::vector<double>& vd = depth[i]->vertex_depth;
        std::sort(all[i].regions.begin(), all[i].regions.end(),
                  [&](const TexelRegion& a, const TexelRegion& b) {
                      return vd[a.seed] > vd[b.seed] ||
                             (vd[a.seed] == vd[b.seed] && a.seed < b.seed);
                  });
        out.push_back(merge_texel_regions(all[i], depth[i]->face_depth, params,
                                          depth[i]->orientation, thresholds[i]));
    }
    return out;
}

}  // namespace

std::vector<TexelSet> make_tiled_texels(const Mesh& mesh, const std::vector<DepthMap>& depth,
                                        const TexelParams& params, int tiles, double halo) {
    if (!(halo >= 0) || !std::isfinite(halo))
        throw InvalidInput("tiles: the halo must be >= 0 and finite");
    std::vector<const DepthMap*> maps;
    for (const DepthMap& d : depth) maps.push_back(&d);
    return tiled_texels(mesh, maps, params, make_tile_boxes(mesh, tiles),
                        halo > 0 ? halo : kTexelHaloRadii * params.radius);
}

namespace {

// A tile's ids of the whole mesh's faces (#F, -1 where the tile has none).
std::vector<int> local_faces(const MeshTile& tile, int num_faces) {
    std::vector<int> local(static_cast<std::size_t>(num_faces), -1);
    for (std::size_t i = 0; i < tile.face.size(); ++i) local[tile.face[i]] = static_cast<int>(i);
    return local;
}

// The texels of `whole` (faces of the whole mesh) as far as they lie in a tile: the same texel
// ids, with the faces the tile holds in its own ids.
TexelSet texels_in_tile(const TexelSet& whole, const std::vector<int>& local_face) {
    TexelSet out;
    out.texels.resize(whole.texels.size());
    for (std::size_t t = 0; t < whole.texels.size(); ++t) {
        Texel& local = out.texels[t];  // the rims read its faces only
        local.orientation = whole.texels[t].orientation;
        for (int f : whole.texels[t].faces)
            if (local_face[f] >= 0) local.faces.push_back(local_face[f]);
    }
    return out;
}

// A depth map of the whole mesh on a tile's vertices and faces; the deepest vertex stays the
// whole mesh's (the features scale depths by it).
DepthMap depth_in_tile(const DepthMap& whole, const MeshTile& tile) {
    DepthMap d;
    d.orientation = whole.orientation;
    d.vertex_depth = restricted(whole.vertex_depth, tile.vertex);
    d.face_depth = restricted(whole.face_depth, tile.face);
    d.max_depth = whole.max_depth;
    d.num_moved_vertices = whole.num_moved_vertices;
    return d;
}

std::size_t index_of(DetailOrientation o) { return o == DetailOrientation::Positive ? 0 : 1; }

// make_rims' flags or-ed over the tiles, each evaluating the vertices it owns.
RimFlags tiled_rim_flags(const Mesh& mesh, const TileBoxes& boxes, double halo,
                         const std::array<TexelSet, 2>& sets, const std::array<DepthMap, 2>& depths,
                         const RimParams& rp) {
    const std::vector<double> pd = texel_depths(mesh, sets[0], depths[0]);
    const std::vector<double> nd = texel_depths(mesh, sets[1], depths[1]);
    RimFlags all;
    all.positive_rim.assign(sets[0].texels.size(), 0);
    all.negative_rim.assign(sets[1].texels.size(), 0);
    all.positive_makes_rim.assign(sets[0].texels.size(), 0);
    all.negative_makes_rim.assign(sets[1].texels.size(), 0);
    if (sets[0].texels.empty() || sets[1].texels.empty()) return all;
    for (int b = 0; b < boxes.size(); ++b) {
        const MeshTile tile = make_mesh_tile(mesh, boxes, b, halo);
        if (tile.mesh.faces.empty()) continue;
        const MeshTopology topology = make_topology(tile.mesh);
        const std::vector<int> local = local_faces(tile, mesh.num_faces());
        const RimFlags f = find_rims(tile.mesh, topology, texels_in_tile(sets[0], local), pd,
                                     texels_in_tile(sets[1], local), nd, rp, tile.owned_vertex);
        const auto merge = [](std::vector<char>& into, const std::vector<char>& from) {
            for (std::size_t t = 0; t < into.size(); ++t) into[t] = into[t] || from[t];
        };
        merge(all.positive_rim, f.positive_rim);
        merge(all.negative_rim, f.negative_rim);
        merge(all.positive_makes_rim, f.positive_makes_rim);
        merge(all.negative_makes_rim, f.negative_makes_rim);
    }
    return all;
}

// Curvature at the texels' vertices and the texels' feature rows, each texel in the tile that
// owns its first face, with a halo that holds the texel and the curvature discs around it.
void tiled_curvature_and_features(const Mesh& mesh, const TileBoxes& boxes, double halo,
                                  const SegmentationParams& params, double largest_side,
                                  Segmentation& seg, FeatureRows& rows) {
    const int nt = static_cast<int>(seg.texels.size());
    const double rho = params.curvature_scale * seg.radius;
    std::vector<std::vector<int>> assigned(static_cast<std::size_t>(boxes.size()));
    std::vector<double> reach(static_cast<std::size_t>(boxes.size()), 0.0);
    for (int t = 0; t < nt; ++t) {
        const auto& f0 = mesh.faces[seg.texels[t].faces.front()];
        const int b = boxes.box_of(
            (mesh.positions[f0[0]] + mesh.positions[f0[1]] + mesh.positions[f0[2]]) / 3.0);
        assigned[b].push_back(t);
        for (int f : seg.texels[t].faces)
            for (int v : mesh.faces[f])
                reach[b] = std::max(reach[b], boxes.distance(b, mesh.positions[v]));
    }
    const std::size_t nv = mesh.positions.size();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    seg.curvature.gaussian.assign(nv, nan);
    seg.curvature.mean.assign(nv, nan);
    seg.curvature.shape_index.assign(nv, nan);
    seg.curvature.curvedness.assign(nv, nan);
    rows.values = Eigen::MatrixXd::Zero(nt, kNumFeatures);
    rows.diameters.assign(static_cast<std::size_t>(nt), {});
    rows.no_contour.assign(static_cast<std::size_t>(nt), 0);
    rows.no_curvature.assign(static_cast<std::size_t>(nt), 0);
    for (int b = 0; b < boxes.size(); ++b) {
        if (assigned[b].empty()) continue;
        // A vertex within rho of a texel's vertex along the mesh is within rho in space: the
        // slack covers the rounding of the two distances.
        const double width = std::max(halo, (reach[b] + rho) * (1 + 1e-9));
        const MeshTile tile = make_mesh_tile(mesh, boxes, b, width);
        const MeshTopology topology = make_topology(tile.mesh);
        const MeshMetrics metrics = make_mesh_metrics(tile.mesh, topology);
        const std::vector<int> local = local_faces(tile, mesh.num_faces());
        std::vector<Texel> texels;
        CurvatureParams cp;
        cp.radius = rho;
        cp.only.assign(tile.vertex.size(), 0);
        for (int t : assigned[b]) {
            Texel local_texel = seg.texels[t];
            for (int& f : local_texel.faces) {
                f = local[f];
                for (int v : tile.mesh.faces[f]) cp.only[v] = 1;
            }
            local_texel.seed = -1;
            texels.push_back(std::move(local_texel));
        }
        const CurvatureField curvature =
            make_curvature(tile.mesh, topology, metrics.vertex_normal, cp);
        for (std::size_t v = 0; v < tile.vertex.size(); ++v)
            if (cp.only[v]) {
                const int w = tile.vertex[v];
                seg.curvature.gaussian[w] = curvature.gaussian[v];
                seg.curvature.mean[w] = curvature.mean[v];
                seg.curvature.shape_index[w] = curvature.shape_index[v];
                seg.curvature.curvedness[w] = curvature.curvedness[v];
            }
        std::optional<DepthMap> positive, negative;
        if (seg.positive_depth) positive = depth_in_tile(*seg.positive_depth, tile);
        if (seg.negative_depth) negative = depth_in_tile(*seg.negative_depth, tile);
        FeatureInputs in;
        in.mesh = &tile.mesh;
        in.topology = &topology;
        in.curvature = &curvature;
        in.positive_depth = positive ? &*positive : nullptr;
        in.negative_depth = negative ? &*negative : nullptr;
        in.largest_side = largest_side;
        FeatureRows part = make_feature_rows(in, texels);
        for (std::size_t k = 0; k < assigned[b].size(); ++k) {
            const int t = assigned[b][k];
            rows.values.row(t) = part.values.row(static_cast<Eigen::Index>(k));
            rows.diameters[t] = std::move(part.diameters[k]);
            rows.no_contour[t] = part.no_contour[k];
            rows.no_curvature[t] = part.no_curvature[k];
        }
    }
}

}  // namespace

Segmentation run_tiled_segmentation(const Mesh& mesh, const SegmentationParams& params, int tiles,
                                    const StageObserver& observer) {
    if (mesh.num_faces() == 0) throw InvalidInput("segmentation: the mesh has no face");
    check_segmentation_params(params);
    if (std::abs(make_unit_frame(mesh.positions).exponent) > 32)
        throw InvalidInput(
            "tiles: the mesh's size is beyond 2^32 or below 2^-32 units; scale it "
            "first or segment it whole");
    const TileBoxes boxes = make_tile_boxes(mesh, tiles);
    Segmentation seg;
    seg.metrics = make_mesh_metrics(mesh);
    seg.radius = resolve_radius(params, seg.metrics.largest_side);
    if (auto d = detail::radius_diagnostic(seg.radius, seg.metrics.mean_edge_length))
        seg.diagnostics.push_back(std::move(*d));
    seg.runs = detail::orientations_of(params.orientation);
    seg.run_excluded_texels.assign(seg.runs.size(), 0);

    const SmoothingParams sp = detail::smoothing_params(params, seg.radius);
    const TexelParams tp = detail::texel_params(params, seg.radius);
    const RimParams rp = detail::rim_params(seg.radius);
    const double depth_halo = kDepthHaloRadii * seg.radius;
    const WholeMeshChoices whole = whole_mesh_choices(mesh, sp);

    // Both orientations when rims are removed: the whole run's rim check is a bound that only
    // spares work, and make_rims leaves nothing out wherever it says no.
    const std::vector<DetailOrientation> first =
        params.remove_rims ? std::vector<DetailOrientation>{DetailOrientation::Positive,
                                                            DetailOrientation::Negative}
                           : seg.runs;
    std::array<DepthMap, 2> depth;
    std::array<TexelSet, 2> texels;
    detail::timed(observer, "depth maps (tiles)", [&] {
        DiscCounts counts;
        std::vector<DepthMap> maps =
            tiled_depth_maps(mesh, sp, first, boxes, depth_halo, whole, {}, &counts);
        seg.num_interpolated_vertices = counts.interpolated;
        seg.num_disc_samples = counts.samples;
        for (std::size_t i = 0; i < first.size(); ++i)
            depth[index_of(first[i])] = std::move(maps[i]);
    });
    // The texels of the orientations in `which`, from their depth maps.
    const auto make_texels_of = [&](const std::vector<DetailOrientation>& which) {
        std::vector<const DepthMap*> maps;
        for (DetailOrientation o : which) maps.push_back(&depth[index_of(o)]);
        std::vector<TexelSet> sets =
            tiled_texels(mesh, maps, tp, boxes, kTexelHaloRadii * seg.radius);
        for (std::size_t i = 0; i < which.size(); ++i)
            texels[index_of(which[i])] = std::move(sets[i]);
    };
    detail::timed(observer, "texels (tiles)", [&] { make_texels_of(first); });
    if (params.remove_rims) {
        RimFlags flags;
        detail::timed(observer, "rims (tiles)",
                      [&] { flags = tiled_rim_flags(mesh, boxes, depth_halo, texels, depth, rp); });
        // For each run, the texels of the other orientation to leave out of its smoothing.
        std::array<std::vector<char>, 2> use;
        std::vector<DetailOrientation> again;
        for (std::size_t r = 0; r < seg.runs.size(); ++r) {
            const bool positive = seg.runs[r] == DetailOrientation::Positive;
            const std::vector<char>& makes =
                positive ? flags.negative_makes_rim : flags.positive_makes_rim;
            const std::vector<char>& rim = positive ? flags.negative_rim : flags.positive_rim;
            std::vector<char>& u = use[index_of(seg.runs[r])];
            u.assign(makes.size(), 0);
            int count = 0;
            for (std::size_t t = 0; t < makes.size(); ++t) {
                u[t] = makes[t] && !rim[t] ? 1 : 0;
                count += u[t];
            }
            seg.run_excluded_texels[r] = count;
            if (count > 0) again.push_back(seg.runs[r]);
        }
        if (!again.empty()) {
            const TileExclusion exclude = [&](const MeshTile& tile, const MeshTopology& topology,
                                              DetailOrientation o) {
                const std::size_t other = 1 - index_of(o);
                return rim_detail_vertices(
                    tile.mesh, topology,
                    texels_in_tile(texels[other], local_faces(tile, mesh.num_faces())),
                    use[index_of(o)], rp);
            };
            detail::timed(observer, "depth maps (tiles, without rims)", [&] {
                std::vector<DepthMap> maps =
                    tiled_depth_maps(mesh, sp, again, boxes, depth_halo, whole, exclude);
                for (std::size_t i = 0; i < again.size(); ++i)
                    depth[index_of(again[i])] = std::move(maps[i]);
            });
            detail::timed(observer, "texels (tiles, without rims)", [&] { make_texels_of(again); });
        }
    }
    std::vector<detail::OrientationResult> results;
    for (DetailOrientation o : seg.runs)
        results.push_back({o, std::move(depth[index_of(o)]), std::move(texels[index_of(o)])});
    const std::vector<std::pair<int, int>> ranges =
        detail::collect_texels(seg, mesh.num_faces(), params.min_faces, std::move(results));
    detail::timed(observer, "curvature and features (tiles)", [&] {
        FeatureRows rows;
        tiled_curvature_and_features(mesh, boxes, depth_halo, params, seg.metrics.largest_side, seg,
                                     rows);
        seg.features = normalise_feature_rows(std::move(rows));
        for (const auto& d : seg.features.diagnostics) seg.diagnostics.push_back(d);
    });
    detail::timed(observer, "clustering", [&] {
        detail::cluster_textures(seg, mesh.num_faces(), ranges, params.clustering);
    });
    return seg;
}

}  // namespace geotex
