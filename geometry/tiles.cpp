#include "geometry/tiles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "common/release.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/tile_steps.hpp"
#include "geometry/disc_means.hpp"
#include "geometry/topology.hpp"

namespace geotex {

int TileBoxes::box_of(const Eigen::Vector3d& p) const {
    const int x = detail::cell_of(p.x(), lo.x(), hi.x(), count[0]);
    const int y = detail::cell_of(p.y(), lo.y(), hi.y(), count[1]);
    const int z = detail::cell_of(p.z(), lo.z(), hi.z(), count[2]);
    return (z * count[1] + y) * count[0] + x;
}

double TileBoxes::distance(int b, const Eigen::Vector3d& p) const {
    const auto [from, to] = corners(b);
    return distance(from, to, p);
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> TileBoxes::corners(int b) const {
    const int cell[3] = {b % count[0], (b / count[0]) % count[1], b / (count[0] * count[1])};
    Eigen::Vector3d from, to;
    for (int axis = 0; axis < 3; ++axis) {
        const double width = (hi[axis] - lo[axis]) / count[axis];
        from[axis] = lo[axis] + cell[axis] * width;
        to[axis] = from[axis] + width;
    }
    return {from, to};
}

TileBoxes make_tile_boxes(PositionSpan positions, int count) {
    if (count < 1)
        throw InvalidInput("tiles: the number of tiles must be at least 1 (got " +
                           std::to_string(count) + ")");
    if (positions.empty()) throw InvalidInput("tiles: the mesh has no vertex");
    TileBoxes boxes;
    const Eigen::AlignedBox3d bounds = bounding_box(positions);
    boxes.lo = bounds.min();
    boxes.hi = bounds.max();
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

namespace detail {

int face_box(const Mesh& mesh, const TileBoxes& boxes, int f) {
    return face_box(mesh.positions, boxes, mesh.faces[f]);
}

int face_box(PositionSpan positions, const TileBoxes& boxes, const std::array<int, 3>& fv) {
    return boxes.box_of((positions[fv[0]] + positions[fv[1]] + positions[fv[2]]) / 3.0);
}

void check_tile_request(const TileBoxes& boxes, int index, double halo) {
    if (index < 0 || index >= boxes.size())
        throw InvalidInput("tiles: tile " + std::to_string(index) + " is not in [0, " +
                           std::to_string(boxes.size()) + ")");
    if (!(halo >= 0) || !std::isfinite(halo))
        throw InvalidInput("tiles: the halo must be >= 0 and finite");
}

MeshTile gathered_tile(const Mesh& mesh, const std::vector<char>& where,
                       const std::vector<char>& taken) {
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    // The lists are sized before they are filled: grown by push_back they would hold up to
    // twice their size, and a texel job holds a cut beside its tile.
    MeshTile tile;
    const auto num_taken = std::count_if(taken.begin(), taken.end(), [](char t) { return t != 0; });
    tile.face.reserve(static_cast<std::size_t>(num_taken));
    tile.owned_face.reserve(static_cast<std::size_t>(num_taken));
    for (int f = 0; f < nf; ++f)
        if (taken[f]) {
            tile.face.push_back(f);
            tile.owned_face.push_back(taken[f] == 2 ? 1 : 0);
        }
    // The tile's vertices in the whole mesh's order, and each one's number in the tile.
    std::vector<int> local(static_cast<std::size_t>(nv), -1);
    for (int f : tile.face)
        for (int v : mesh.faces[f]) local[v] = 0;
    tile.vertex.reserve(static_cast<std::size_t>(std::count(local.begin(), local.end(), 0)));
    for (int v = 0; v < nv; ++v)
        if (local[v] == 0) {
            local[v] = static_cast<int>(tile.vertex.size());
            tile.vertex.push_back(v);
        }
    tile.mesh.positions = detail::restricted(mesh.positions, tile.vertex);
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

}  // namespace detail

MeshTile make_mesh_tile(const Mesh& mesh, const TileBoxes& boxes, int index, double halo,
                        const KnownOwned& known) {
    detail::check_tile_request(boxes, index, halo);
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    const bool is_known = known.vertex || known.face;
    if (is_known &&
        (!known.vertex || !known.face || known.vertex->size() != mesh.positions.size() ||
         known.face->size() != mesh.faces.size()))
        throw InvalidInput("tiles: the known owners do not match the mesh's vertices and faces");
    // 1: the vertex is in the box, 2: within the halo of it, 0: neither.
    std::vector<char> where(static_cast<std::size_t>(nv), 0);
    detail::parallel_for(nv, [&](int v) {
        const Eigen::Vector3d& p = mesh.positions[v];
        const bool owned = is_known ? (*known.vertex)[v] != 0 : boxes.box_of(p) == index;
        where[v] = owned ? 1 : boxes.distance(index, p) <= halo ? 2 : 0;
    });
    // 2: the face is owned (its centroid is in the box), 1: it has a vertex within the halo,
    // 0: neither. Decided in parallel, gathered in face order.
    std::vector<char> taken(static_cast<std::size_t>(nf), 0);
    detail::parallel_for(nf, [&](int f) {
        const auto& fv = mesh.faces[f];
        const bool owned =
            is_known ? (*known.face)[f] != 0 : detail::face_box(mesh, boxes, f) == index;
        taken[f] = owned ? 2 : where[fv[0]] || where[fv[1]] || where[fv[2]] ? 1 : 0;
    });
    return detail::gathered_tile(mesh, where, taken);
}

namespace detail {

namespace {

DiscMeanParams disc_params(const SmoothingParams& params) {
    DiscMeanParams disc;
    disc.radius = params.radius;
    disc.mode = params.disc;
    return disc;
}

}  // namespace

WholeMeshChoices whole_mesh_choices(const Mesh& mesh, const SmoothingParams& params) {
    VertexComponents components = vertex_components(mesh);
    DiscSampling sampling = make_disc_sampling(mesh, disc_params(params), &components);
    return {std::move(sampling), std::move(components)};
}

WholeMeshChoices whole_mesh_choices(PositionSpan positions, const FaceBlockReader& faces,
                                    std::size_t num_faces, const SmoothingParams& params) {
    VertexComponents components =
        vertex_components(static_cast<int>(positions.size()), faces, num_faces);
    DiscSampling sampling =
        make_disc_sampling(positions, faces, num_faces, disc_params(params), components);
    return {std::move(sampling), std::move(components)};
}

SpooledChoices::SpooledChoices(const WholeMeshChoices& whole, const int* ids,
                               std::size_t num_vertices, const std::string& dir)
    : file_(dir) {
    // A block at a time: the scratch file writes what it buffers as it fills.
    constexpr std::size_t kBlock = std::size_t{1} << 16;
    std::vector<int> block;
    block.reserve(kBlock);
    for (std::size_t first = 0; first < num_vertices; first += kBlock) {
        const std::size_t end = std::min(num_vertices, first + kBlock);
        block.clear();
        for (std::size_t k = first; k < end; ++k) {
            const auto v = static_cast<std::size_t>(ids ? ids[k] : static_cast<int>(k));
            const int c = whole.components.component[v];
            block.push_back(whole.sampling.fast[v] != 0 ? ~c : c);
        }
        file_.append(block.data(), block.size());
    }
    values_ = file_.map();
    outline_.sampling = {{}, whole.sampling.origin, whole.sampling.grid};
    outline_.components = {{}, whole.components.num_components};
}

DepthTile make_depth_tile(const Mesh& mesh, const TileBoxes& boxes, int b, double halo,
                          double radius, const WholeMeshChoices& whole, MeshTiler* tiler) {
    return make_depth_tile(tiler ? tiler->tile(b, halo) : make_mesh_tile(mesh, boxes, b, halo),
                           mesh.num_vertices(), boxes, b, halo, radius, whole);
}

DepthTile make_depth_tile(MeshTile tile, int num_vertices, const TileBoxes& boxes, int b,
                          double halo, double radius, const WholeMeshChoices& whole) {
    DepthTile out;
    out.tile = b;
    out.boxes = boxes;
    out.mesh_vertices = num_vertices;
    out.radius = radius;
    out.halo = halo;
    out.mesh = std::move(tile);
    out.sampling = {restricted(whole.sampling.fast, out.mesh.vertex), whole.sampling.origin,
                    whole.sampling.grid};
    out.components = {restricted(whole.components.component, out.mesh.vertex),
                      whole.components.num_components};
    return out;
}

DepthTile narrowed_depth_tile(const DepthTile& tile, double halo) {
    if (!(halo <= tile.halo)) throw InvalidInput("tiles: a tile cannot be cut to a wider halo");
    // The tile's mesh holds every face the narrower halo takes from the whole mesh, in the
    // whole mesh's order, so the cut is the whole mesh's tile once its ids are the whole's.
    DepthTile out;
    out.tile = tile.tile;
    out.boxes = tile.boxes;
    out.mesh_vertices = tile.mesh_vertices;
    out.radius = tile.radius;
    out.halo = halo;
    // Which vertices and faces lie in the tile's own box is known from the wider cut, so their
    // boxes are not found again.
    out.mesh = make_mesh_tile(tile.mesh.mesh, tile.boxes, tile.tile, halo,
                              {&tile.mesh.owned_vertex, &tile.mesh.owned_face});
    out.sampling = {restricted(tile.sampling.fast, out.mesh.vertex), tile.sampling.origin,
                    tile.sampling.grid};
    out.components = {restricted(tile.components.component, out.mesh.vertex),
                      tile.components.num_components};
    for (int& v : out.mesh.vertex) v = tile.mesh.vertex[v];
    for (int& f : out.mesh.face) f = tile.mesh.face[f];
    return out;
}

TilePart depth_part(DepthTile input, const SmoothingParams& params,
                    const std::vector<DetailOrientation>& orientations,
                    const TileExclusion& exclude, bool count) {
    MeshTile& tile = input.mesh;
    TilePart part;
    part.tile = input.tile;
    part.depths.resize(orientations.size());
    part.moved.assign(orientations.size(), 0);
    if (tile.mesh.faces.empty()) return part;
    for (std::size_t v = 0; v < tile.vertex.size(); ++v)
        if (tile.owned_vertex[v]) part.vertices.push_back(tile.vertex[v]);
    const std::size_t nv = tile.mesh.positions.size();
    // The smoothed surfaces (one shared by the orientations, or one each when texels are
    // excluded from it) are made first, so that the smoothing's topology, metrics and disc
    // averager are released before the depths are mapped: held beside the mapping, they
    // were most of a depth job's peak.
    std::vector<SmoothedSurface> smoothed;
    std::vector<Eigen::Vector3d> vertex_normal;
    {
        // The smoothing walks the vertices' neighbours alone and weighs by the vertices' areas,
        // and the mapping reads the vertices' normals: the topology keeps those rows only, and
        // the metrics are made without it (the same bits), the faces' areas dropped.
        MeshMetrics metrics = make_mesh_metrics(tile.mesh);
        release(metrics.face_area);
        const MeshTopology topology = make_topology(tile.mesh, TopologyRows::VertexNeighbours);
        // The exclusions are the last to read the cut's ids in the whole mesh: the smoothing
        // and the mapping read its mesh and which vertices it owns alone, so the ids and the
        // other flags (5 bytes a face and 5 a vertex) go before the smoothing's peak.
        std::vector<std::vector<char>> excluded;
        if (exclude)
            for (DetailOrientation o : orientations) excluded.push_back(exclude(tile, topology, o));
        release(tile.vertex);
        release(tile.face);
        release(tile.owned_face);
        release(tile.complete_vertex);
        SmoothingParams sp = params;
        sp.sampling = &input.sampling;
        const SurfaceSmoother smoother(tile.mesh, topology, metrics, sp);
        release(metrics.vertex_area);  // the smoother keeps its weights
        if (count) {
            const DiscAverager& averager = smoother.averager();
            for (std::size_t v = 0; v < nv; ++v)
                if (tile.owned_vertex[v] && averager.interpolated(static_cast<int>(v)))
                    ++part.interpolated;
            for (int v : averager.sample_vertices()) part.samples += tile.owned_vertex[v];
        }
        if (!exclude)
            smoothed.push_back(smoother.smooth());
        else
            for (const std::vector<char>& e : excluded) smoothed.push_back(smoother.smooth(e));
        vertex_normal = std::move(metrics.vertex_normal);
    }
    input.sampling = DiscSampling();
    const DepthMapper mapper(tile.mesh, std::move(input.components));
    for (std::size_t i = 0; i < orientations.size(); ++i) {
        const SmoothedSurface& surface = exclude ? smoothed[i] : smoothed.front();
        const DepthMap d = mapper.map(vertex_normal, surface, orientations[i]);
        for (std::size_t v = 0; v < nv; ++v) {
            if (!tile.owned_vertex[v]) continue;
            part.depths[i].push_back(d.vertex_depth[v]);
            if (stands_out(tile.mesh.positions[v], surface.positions[v], vertex_normal[v],
                           orientations[i]))
                ++part.moved[i];
        }
    }
    return part;
}

std::vector<DepthMap> empty_depth_maps(const Mesh& mesh,
                                       const std::vector<DetailOrientation>& orientations) {
    std::vector<DepthMap> maps(orientations.size());
    for (std::size_t i = 0; i < maps.size(); ++i) {
        maps[i].orientation = orientations[i];
        maps[i].vertex_depth.assign(mesh.positions.size(), 0.0);
    }
    return maps;
}

void add_depth_part(const TilePart& part, std::vector<DepthMap*> maps) {
    for (std::size_t i = 0; i < maps.size(); ++i) {
        for (std::size_t k = 0; k < part.vertices.size(); ++k)
            maps[i]->vertex_depth[part.vertices[k]] = part.depths[i][k];
        maps[i]->num_moved_vertices += part.moved[i];
    }
}

}  // namespace detail

std::vector<DepthMap> make_tiled_depth_maps(const Mesh& mesh, const SmoothingParams& params,
                                            const std::vector<DetailOrientation>& orientations,
                                            int tiles, double halo) {
    if (!(halo >= 0) || !std::isfinite(halo))
        throw InvalidInput("tiles: the halo must be >= 0 and finite");
    const TileBoxes boxes = make_tile_boxes(mesh.positions, tiles);
    const detail::WholeMeshChoices whole = detail::whole_mesh_choices(mesh, params);
    std::vector<DepthMap> maps = detail::empty_depth_maps(mesh, orientations);
    std::vector<DepthMap*> into;
    for (DepthMap& d : maps) into.push_back(&d);
    for (int b = 0; b < boxes.size(); ++b)
        detail::add_depth_part(
            detail::depth_part(
                detail::make_depth_tile(mesh, boxes, b,
                                        halo > 0 ? halo : kDepthHaloRadii * params.radius,
                                        params.radius, whole),
                params, orientations, {}, false),
            into);
    for (DepthMap& d : maps) set_face_depths(mesh, d);
    return maps;
}

}  // namespace geotex
