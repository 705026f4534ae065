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

}  // namespace detail

MeshTile make_mesh_tile(const Mesh& mesh, const TileBoxes& boxes, int index, double halo,
                        const MeshBoxes* known) {
    detail::check_tile_request(boxes, index, halo);
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    if (known &&
        (known->vertex.size() != mesh.positions.size() || known->face.size() != mesh.faces.size()))
        throw InvalidInput("tiles: the known boxes do not match the mesh's vertices and faces");
    // 1: the vertex is in the box, 2: within the halo of it, 0: neither.
    std::vector<char> where(static_cast<std::size_t>(nv), 0);
    detail::parallel_for(nv, [&](int v) {
        const Eigen::Vector3d& p = mesh.positions[v];
        const int box = known ? known->vertex[v] : boxes.box_of(p);
        where[v] = box == index ? 1 : boxes.distance(index, p) <= halo ? 2 : 0;
    });
    // 2: the face is owned (its centroid is in the box), 1: it has a vertex within the halo,
    // 0: neither. Decided in parallel, gathered in face order.
    std::vector<char> taken(static_cast<std::size_t>(nf), 0);
    detail::parallel_for(nf, [&](int f) {
        const auto& fv = mesh.faces[f];
        const int box = known ? known->face[f] : detail::face_box(mesh, boxes, f);
        taken[f] = box == index ? 2 : where[fv[0]] || where[fv[1]] || where[fv[2]] ? 1 : 0;
    });
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
    // boxes are not found again: make_mesh_tile asks of a box only whether it is the tile's.
    MeshBoxes known;
    known.vertex.resize(tile.mesh.owned_vertex.size());
    known.face.resize(tile.mesh.owned_face.size());
    detail::parallel_for(static_cast<int>(known.vertex.size()), [&](int v) {
        known.vertex[v] = tile.mesh.owned_vertex[v] ? tile.tile : -1;
    });
    detail::parallel_for(static_cast<int>(known.face.size()),
                         [&](int f) { known.face[f] = tile.mesh.owned_face[f] ? tile.tile : -1; });
    out.mesh = make_mesh_tile(tile.mesh.mesh, tile.boxes, tile.tile, halo, &known);
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
    const MeshTile& tile = input.mesh;
    TilePart part;
    part.tile = input.tile;
    part.depths.resize(orientations.size());
    part.moved.assign(orientations.size(), 0);
    if (tile.mesh.faces.empty()) return part;
    for (std::size_t v = 0; v < tile.vertex.size(); ++v)
        if (tile.owned_vertex[v]) part.vertices.push_back(tile.vertex[v]);
    // The smoothed surfaces (one shared by the orientations, or one each when texels are
    // excluded from it) are made first, so that the smoothing's topology, metrics and disc
    // averager are released before the depths are mapped: held beside the mapping, they
    // were most of a depth job's peak.
    std::vector<SmoothedSurface> smoothed;
    std::vector<Eigen::Vector3d> vertex_normal;
    {
        // Neither the smoothing nor the mapping walks the faces' neighbours, nor weighs by the
        // faces' areas.
        const MeshTopology topology = make_topology(tile.mesh, TopologyRows::WithoutFaceNeighbours);
        MeshMetrics metrics = make_mesh_metrics(tile.mesh, topology);
        metrics.face_area = std::vector<double>();
        SmoothingParams sp = params;
        sp.sampling = &input.sampling;
        const SurfaceSmoother smoother(tile.mesh, topology, metrics, sp);
        if (count) {
            const DiscAverager& averager = smoother.averager();
            for (std::size_t v = 0; v < tile.vertex.size(); ++v)
                if (tile.owned_vertex[v] && averager.interpolated(static_cast<int>(v)))
                    ++part.interpolated;
            for (int v : averager.sample_vertices()) part.samples += tile.owned_vertex[v];
        }
        if (!exclude)
            smoothed.push_back(smoother.smooth());
        else
            for (DetailOrientation o : orientations)
                smoothed.push_back(smoother.smooth(exclude(tile, topology, o)));
        vertex_normal = std::move(metrics.vertex_normal);
    }
    input.sampling = DiscSampling();
    const DepthMapper mapper(tile.mesh, std::move(input.components));
    for (std::size_t i = 0; i < orientations.size(); ++i) {
        const SmoothedSurface& surface = exclude ? smoothed[i] : smoothed.front();
        const DepthMap d = mapper.map(vertex_normal, surface, orientations[i]);
        for (std::size_t v = 0; v < tile.vertex.size(); ++v) {
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

namespace detail {

std::optional<TilePart> texel_part(const Mesh& mesh, const std::vector<const DepthMap*>& depth,
                                   const std::vector<double>& thresholds, const TexelParams& params,
                                   const TileBoxes& boxes, int b, double width, double max_width,
                                   MeshTile* mesh_tile, std::vector<DepthMap>* tile_maps,
                                   const std::function<Mesh()>& read_mesh_again) {
    // A region that grows onto a face whose neighbours the tile may not all hold could have
    // grown further in the whole mesh: the tile is made again with twice the halo until none
    // does (at worst it holds the whole mesh, where every region is whole).
    TilePart part;
    part.tile = b;
    part.thresholds = thresholds;
    part.regions.resize(depth.size());
    part.region_depths.resize(depth.size());
    if (width > max_width) return std::nullopt;
    MeshTile cut;
    std::vector<DepthMap> local(depth.size());
    // What the regions grew in last: `cut` and `local`, or the given tile and maps themselves.
    const MeshTile* tile = &cut;
    std::vector<const DepthMap*> maps(depth.size());
    // The tile's mesh is let go while the regions grow in a cut of it, when it can be read
    // again (a tile job): its positions and faces are most of what the job holds beside the cut.
    const bool let_go = mesh_tile && read_mesh_again && &mesh == &mesh_tile->mesh;
    bool released = false;
    for (double w = width;; w *= 2) {
        if (released) {
            cut = MeshTile();  // the narrower cut, not held beside the tile read again
            for (DepthMap& d : local) d = DepthMap();
            mesh_tile->mesh = read_mesh_again();  // `mesh` refers to it
            released = false;
            if (mesh_tile->mesh.positions.size() != mesh_tile->vertex.size() ||
                mesh_tile->mesh.faces.size() != mesh_tile->face.size())
                throw InvalidInput("tiles: tile " + std::to_string(b + 1) +
                                   "'s mesh read again is not the one read first");
        }
        // A tile's own mesh cut to its halo is the same tile, face for face and flag for flag
        // (make_mesh_tile's tests are geometric): at the widest cut of a tile job, the largest,
        // the tile is grown in as it is, which spares a copy of it and of its depth maps.
        const bool itself = mesh_tile && w == max_width;
        if (itself) {
            tile = mesh_tile;
            cut = MeshTile();  // the narrower cut and its maps, not held beside the tile
            for (std::size_t i = 0; i < depth.size(); ++i) {
                local[i] = DepthMap();
                maps[i] = depth[i];
                if (!depth[i]->face_depth.empty()) continue;
                // The tile's maps get their face depths here, in place, now that no cut's are held.
                if (!tile_maps || tile_maps->size() != depth.size() || &(*tile_maps)[i] != depth[i])
                    throw InvalidInput("tiles: a tile's depth map has no face depths to grow in");
                set_face_depths(tile->mesh, (*tile_maps)[i]);
            }
        } else {
            cut = make_mesh_tile(mesh, boxes, b, w);
            tile = &cut;
            if (let_go) {
                mesh_tile->mesh = Mesh();
                released = true;
            }
        }
        if (tile->mesh.faces.empty()) break;
        const MeshTopology topology = make_topology(tile->mesh);
        bool whole = true;
        for (std::size_t i = 0; i < depth.size() && whole; ++i) {
            if (!itself) {
                local[i].orientation = depth[i]->orientation;
                local[i].vertex_depth = restricted(depth[i]->vertex_depth, cut.vertex);
                // Made from the cut's vertex depths where the map has none: each face's mean of
                // the same three depths in the same order, so the bits restriction would give.
                if (depth[i]->face_depth.empty())
                    set_face_depths(cut.mesh, local[i]);
                else
                    local[i].face_depth = restricted(depth[i]->face_depth, cut.face);
                maps[i] = &local[i];
            }
            part.regions[i] = grow_texel_regions(tile->mesh, topology, *maps[i], params,
                                                 thresholds[i], tile->owned_vertex);
            for (const TexelRegion& r : part.regions[i].regions)
                for (int f : r.faces)
                    for (int v : tile->mesh.faces[f]) whole = whole && tile->complete_vertex[v];
        }
        if (whole) break;
        // A tile of a halo `max_width` wide holds the faces of a halo up to that, not beyond;
        // a narrower halo than the whole run's next would give other regions.
        if (2 * w > max_width) return std::nullopt;
    }
    for (std::size_t i = 0; i < depth.size(); ++i) {
        // A tile without faces grew no region, and no map was chosen for it.
        if (part.regions[i].regions.empty()) continue;
        RegionDepths& d = part.region_depths[i];
        const std::vector<double>& vd = maps[i]->vertex_depth;
        for (const TexelRegion& r : part.regions[i].regions) {
            d.seed.push_back(vd[r.seed]);
            for (int f : r.faces) {
                const auto& corners = tile->mesh.faces[f];
                d.face.push_back(maps[i]->face_depth[f]);
                d.peak.push_back(std::max({vd[corners[0]], vd[corners[1]], vd[corners[2]]}));
            }
        }
    }
    // Grown in the given tile itself, the regions are in its ids already.
    if (tile == &cut) renumber_regions(part.regions, cut.vertex, cut.face);
    return part;
}

void renumber_regions(std::vector<TexelRegions>& regions, const std::vector<int>& vertex,
                      const std::vector<int>& face) {
    for (TexelRegions& grown : regions)
        for (TexelRegion& r : grown.regions) {
            r.seed = vertex[r.seed];
            for (int& f : r.faces) f = face[f];
            for (int& f : r.touch) f = face[f];
        }
}

TexelSet merge_tile_regions(TexelRegions all, const DepthMap& depth, const TexelParams& params,
                            double threshold) {
    // The order of make_texels: deepest seed first, the lower vertex id on a tie.
    const std::vector<double>& vd = depth.vertex_depth;
    std::sort(all.regions.begin(), all.regions.end(),
              [&](const TexelRegion& a, const TexelRegion& b) {
                  return vd[a.seed] > vd[b.seed] || (vd[a.seed] == vd[b.seed] && a.seed < b.seed);
              });
    return merge_texel_regions(std::move(all), depth.face_depth, params, depth.orientation,
                               threshold);
}

namespace {

// Sorts `faces` (with `depth` and `peak`, one per face) and keeps each face once. Throws
// InvalidInput when a face has two different depths.
void sort_unique_faces(std::vector<int>& faces, std::vector<double>& depth,
                       std::vector<double>& peak) {
    const std::size_t n = faces.size();
    if (n > std::numeric_limits<std::uint32_t>::max())
        throw InvalidInput("tiles: the texel regions have more than 2^32 faces in all");
    std::vector<std::pair<int, std::uint32_t>> order;  // a face and where its depths are
    order.reserve(n);
    for (std::size_t i = 0; i < n; ++i) order.emplace_back(faces[i], static_cast<std::uint32_t>(i));
    std::sort(order.begin(), order.end());
    const auto repeated = [&](std::size_t i) {
        return i > 0 && order[i].first == order[i - 1].first;
    };
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) kept += repeated(i) ? 0 : 1;
    // Each array's values gathered in that order, once a face, one array at a time. Moving
    // them in place, one cycle of the permutation at a time, would spare the copy but is
    // several times slower: each step of a cycle waits for the read before it.
    for (std::vector<double>* values : {&depth, &peak}) {
        std::vector<double> unique(kept);
        std::size_t k = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double v = (*values)[order[i].second];
            if (!repeated(i)) {
                unique[k++] = v;
            } else if (!(unique[k - 1] == v)) {
                // Every tile's depths are the joined maps' at its vertices: the same bits.
                throw InvalidInput("tiles: two texel parts give face " +
                                   std::to_string(order[i].first) + " different depths");
            }
        }
        values->swap(unique);
    }
    faces.resize(kept);
    for (std::size_t i = 0, k = 0; i < n; ++i)
        if (!repeated(i)) faces[k++] = order[i].first;
    faces.shrink_to_fit();
}

}  // namespace

void TexelRegionJoin::add(TexelRegions regions, RegionDepths depths) {
    std::size_t num_faces = 0;
    for (const TexelRegion& r : regions.regions) num_faces += r.faces.size();
    if (depths.seed.size() != regions.regions.size() || depths.face.size() != num_faces ||
        depths.peak.size() != num_faces)
        throw InvalidInput("tiles: the texel parts' depths do not match their regions");
    // The part's claimed faces once each: the regions of a detail's many seeds claim mostly
    // the same faces (at 1% on sphere-1, each face about eight times).
    std::vector<int> claimed;
    claimed.reserve(num_faces);
    for (const TexelRegion& r : regions.regions)
        claimed.insert(claimed.end(), r.faces.begin(), r.faces.end());
    sort_unique_faces(claimed, depths.face, depths.peak);
    face_.insert(face_.end(), claimed.begin(), claimed.end());
    face_depth_.insert(face_depth_.end(), depths.face.begin(), depths.face.end());
    face_peak_.insert(face_peak_.end(), depths.peak.begin(), depths.peak.end());
    // Neighbouring tiles' regions claim the faces of their halos again: once the faces have
    // doubled since they were last made unique, they are made unique again, so that they
    // stay within about twice the faces claimed at the cost of a few more sorts. The first
    // part's are unique already.
    if (face_.size() > claimed.size() && face_.size() >= 2 * unique_faces_) {
        sort_unique_faces(face_, face_depth_, face_peak_);
        unique_faces_ = face_.size();
    }

    for (TexelRegion& r : regions.regions) {
        // Only the faces next to the region: the merge visits its faces as well.
        r.touch.erase(std::set_difference(r.touch.begin(), r.touch.end(), r.faces.begin(),
                                          r.faces.end(), r.touch.begin()),
                      r.touch.end());
        r.touch.shrink_to_fit();
        regions_.push_back(std::move(r));
    }
    num_seeds_ += regions.num_seeds;
    seed_depth_.insert(seed_depth_.end(), depths.seed.begin(), depths.seed.end());
}

TexelSet TexelRegionJoin::merge(const TexelParams& params, DetailOrientation orientation,
                                double threshold, std::vector<double>& texel_depth) {
    // The faces some region claims, ascending and once each, with their depths: merge_texel_
    // regions only orders and compares face ids, so numbering these faces 0, 1, ... in the
    // whole mesh's order merges as the whole mesh does, with arrays as long as the regions
    // rather than #F.
    sort_unique_faces(face_, face_depth_, face_peak_);
    const auto number = [&](int f) { return index_in(face_, f); };

    // The order of make_texels: deepest seed first, the lower vertex id on a tie.
    const std::size_t n = regions_.size();
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    const std::vector<double>& sd = seed_depth_;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const int sa = regions_[a].seed, sb = regions_[b].seed;
        return sd[a] > sd[b] || (sd[a] == sd[b] && sa < sb);
    });
    TexelRegions sorted;
    sorted.num_seeds = num_seeds_;
    sorted.regions.reserve(n);
    for (std::size_t i : order) {
        TexelRegion r = std::move(regions_[i]);
        if (!sorted.regions.empty() && sorted.regions.back().seed == r.seed)
            throw InvalidInput("tiles: two texel parts grow a region from vertex " +
                               std::to_string(r.seed));
        for (int& f : r.faces) f = number(f);
        // A face next to a region that no region claims joins no two regions.
        std::size_t kept = 0;
        for (int f : r.touch)
            if (const int g = number(f); g >= 0) r.touch[kept++] = g;
        r.touch.resize(kept);
        sorted.regions.push_back(std::move(r));
    }
    release(regions_);
    release(seed_depth_);
    num_seeds_ = 0;

    TexelSet set =
        merge_texel_regions(std::move(sorted), face_depth_, params, orientation, threshold);
    release(set.face_texel);  // over the claimed faces' numbers, not the mesh's
    release(face_depth_);
    texel_depth.assign(set.texels.size(), 0.0);
    for (std::size_t t = 0; t < set.texels.size(); ++t)
        for (int& f : set.texels[t].faces) {
            texel_depth[t] = std::max(texel_depth[t], face_peak_[f]);
            f = face_[f];
        }
    release(face_);
    release(face_peak_);
    return set;
}

}  // namespace detail

namespace {

void check_depth_maps(const Mesh& mesh, const std::vector<DepthMap>& depth) {
    for (const DepthMap& d : depth)
        if (d.vertex_depth.size() != mesh.positions.size() ||
            d.face_depth.size() != mesh.faces.size())
            throw InvalidInput("tiles: a depth map does not match the mesh");
}

}  // namespace

std::vector<TexelSet> make_tiled_texels(const Mesh& mesh, const std::vector<DepthMap>& depth,
                                        const TexelParams& params, int tiles, double halo) {
    if (!(halo >= 0) || !std::isfinite(halo))
        throw InvalidInput("tiles: the halo must be >= 0 and finite");
    check_depth_maps(mesh, depth);
    const TileBoxes boxes = make_tile_boxes(mesh.positions, tiles);
    std::vector<const DepthMap*> maps;
    std::vector<double> thresholds;
    for (const DepthMap& d : depth) {
        maps.push_back(&d);
        thresholds.push_back(texel_global_threshold(d.vertex_depth, params));
    }
    std::vector<TexelRegions> all(depth.size());
    for (int b = 0; b < boxes.size(); ++b) {
        TilePart part = *detail::texel_part(mesh, maps, thresholds, params, boxes, b,
                                            halo > 0 ? halo : kTexelHaloRadii * params.radius);
        for (std::size_t i = 0; i < depth.size(); ++i) {
            for (TexelRegion& r : part.regions[i].regions) all[i].regions.push_back(std::move(r));
            all[i].num_seeds += part.regions[i].num_seeds;
        }
    }
    std::vector<TexelSet> out;
    for (std::size_t i = 0; i < depth.size(); ++i)
        out.push_back(
            detail::merge_tile_regions(std::move(all[i]), depth[i], params, thresholds[i]));
    return out;
}

}  // namespace geotex
