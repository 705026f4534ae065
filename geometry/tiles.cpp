#include "geometry/tiles.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/disc_means.hpp"
#include "geometry/topology.hpp"

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

std::vector<DepthMap> make_tiled_depth_maps(const Mesh& mesh, const SmoothingParams& params,
                                            const std::vector<DetailOrientation>& orientations,
                                            int tiles, double halo) {
    if (!(halo >= 0) || !std::isfinite(halo))
        throw InvalidInput("tiles: the halo must be >= 0 and finite");
    const TileBoxes boxes = make_tile_boxes(mesh, tiles);
    const double width = halo > 0 ? halo : kDepthHaloRadii * params.radius;
    // What a tile cannot see of the whole mesh: which discs are sampled, where the sampling
    // grid starts, and which vertices are one connected piece.
    DiscMeanParams disc;
    disc.radius = params.radius;
    disc.mode = params.disc;
    const DiscSampling whole_sampling = make_disc_sampling(mesh, disc);
    const VertexComponents whole_components = vertex_components(mesh);

    const int nv = mesh.num_vertices();
    std::vector<DepthMap> maps(orientations.size());
    for (std::size_t i = 0; i < maps.size(); ++i) {
        maps[i].orientation = orientations[i];
        maps[i].vertex_depth.assign(static_cast<std::size_t>(nv), 0.0);
    }
    for (int b = 0; b < boxes.size(); ++b) {
        const MeshTile tile = make_mesh_tile(mesh, boxes, b, width);
        if (tile.mesh.faces.empty()) continue;
        const MeshTopology topology = make_topology(tile.mesh);
        const MeshMetrics metrics = make_mesh_metrics(tile.mesh, topology);
        DiscSampling sampling{restricted(whole_sampling.fast, tile.vertex), whole_sampling.origin,
                              whole_sampling.grid};
        SmoothingParams sp = params;
        sp.sampling = &sampling;
        const SmoothedSurface smoothed = make_smoothed_surface(tile.mesh, topology, metrics, sp);
        const DepthMapper mapper(tile.mesh, {restricted(whole_components.component, tile.vertex),
                                             whole_components.num_components});
        for (std::size_t i = 0; i < maps.size(); ++i) {
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

std::vector<TexelSet> make_tiled_texels(const Mesh& mesh, const std::vector<DepthMap>& depth,
                                        const TexelParams& params, int tiles, double halo) {
    if (!(halo >= 0) || !std::isfinite(halo))
        throw InvalidInput("tiles: the halo must be >= 0 and finite");
    for (const DepthMap& d : depth)
        if (d.vertex_depth.size() != mesh.positions.size() ||
            d.face_depth.size() != mesh.faces.size())
            throw InvalidInput("tiles: a depth map does not match the mesh");
    const TileBoxes boxes = make_tile_boxes(mesh, tiles);
    const double width = halo > 0 ? halo : kTexelHaloRadii * params.radius;
    std::vector<double> thresholds;
    for (const DepthMap& d : depth)
        thresholds.push_back(texel_global_threshold(d.vertex_depth, params));

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
                local.orientation = depth[i].orientation;
                local.vertex_depth = restricted(depth[i].vertex_depth, tile.vertex);
                local.face_depth = restricted(depth[i].face_depth, tile.face);
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
        const std::vector<double>& vd = depth[i].vertex_depth;
        std::sort(all[i].regions.begin(), all[i].regions.end(),
                  [&](const TexelRegion& a, const TexelRegion& b) {
                      return vd[a.seed] > vd[b.seed] ||
                             (vd[a.seed] == vd[b.seed] && a.seed < b.seed);
                  });
        out.push_back(merge_texel_regions(all[i], depth[i].face_depth, params, depth[i].orientation,
                                          thresholds[i]));
    }
    return out;
}

}  // namespace geotex
