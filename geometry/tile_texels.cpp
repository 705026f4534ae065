// Texels made tile by tile (docs/tiles.md): a tile's texel part, grown in cuts of the mesh
// around its box and around the regions that reach past it, and the join of every tile's
// regions into the whole mesh's texels. tiles.cpp makes the boxes, the tiles and the depth maps.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/release.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/tile_steps.hpp"
#include "geometry/tiles.hpp"
#include "geometry/topology.hpp"

namespace geotex {

namespace detail {

namespace {

// A region grown where every face around its faces was held, so the whole mesh's, in the ids
// of the mesh texel_part was given, with the depths its part carries.
struct FinishedRegion {
    TexelRegion region;
    double seed_depth = 0;
    std::vector<double> face, peak;  // each face's depth and greatest vertex depth
};

// A seed whose region reached the edge of what it grew in: it grows again in a cut of the
// faces with a vertex within `margin` of the box around the region as far as it grew.
struct SeedToRegrow {
    int seed = -1;  // in the ids of the mesh texel_part was given
    Eigen::Vector3d lo, hi;
    double margin = 0;
};

// `region`, grown in `cut` over `map`, with its depths, in the ids of what it was cut from.
FinishedRegion finished_region(TexelRegion region, const MeshTile& cut, const DepthMap& map) {
    FinishedRegion out;
    const std::vector<double>& vd = map.vertex_depth;
    out.seed_depth = vd[region.seed];
    out.face.reserve(region.faces.size());
    out.peak.reserve(region.faces.size());
    for (int f : region.faces) {
        const auto& corners = cut.mesh.faces[f];
        out.face.push_back(map.face_depth[f]);
        out.peak.push_back(std::max({vd[corners[0]], vd[corners[1]], vd[corners[2]]}));
    }
    region.seed = cut.vertex[region.seed];
    for (int& f : region.faces) f = cut.face[f];
    for (int& f : region.touch) f = cut.face[f];
    out.region = std::move(region);
    return out;
}

// Whether every face around the region's faces is in the cut it grew in.
bool region_whole(const TexelRegion& region, const MeshTile& cut) {
    for (int f : region.faces)
        for (int v : cut.mesh.faces[f])
            if (!cut.complete_vertex[v]) return false;
    return true;
}

// `region`, which reached the edge of the cut it grew in, to grow again around it.
SeedToRegrow regrowth_of(const TexelRegion& region, const MeshTile& cut, double margin) {
    const std::vector<Eigen::Vector3d>& p = cut.mesh.positions;
    SeedToRegrow out;
    out.seed = cut.vertex[region.seed];
    out.lo = out.hi = p[region.seed];
    for (int f : region.faces)
        for (int v : cut.mesh.faces[f]) {
            out.lo = out.lo.cwiseMin(p[v]);
            out.hi = out.hi.cwiseMax(p[v]);
        }
    out.margin = margin;
    return out;
}

// The vertices of `positions` within its margin of the box of one of `seeds` (#V, 1 or 0).
// The boxes lie along a tile's edges, each a small part of it: a grid of cells about a margin
// wide lists the boxes that reach each cell, so that a vertex is tested against those near it.
std::vector<char> near_regrowth(const std::vector<Eigen::Vector3d>& positions,
                                const std::vector<SeedToRegrow>& seeds) {
    std::vector<char> near(positions.size(), 0);
    if (seeds.empty()) return near;
    Eigen::Vector3d lo = seeds.front().lo, hi = seeds.front().hi;
    double cell = std::numeric_limits<double>::infinity();
    for (const SeedToRegrow& s : seeds) {
        lo = lo.cwiseMin(s.lo - Eigen::Vector3d::Constant(s.margin));
        hi = hi.cwiseMax(s.hi + Eigen::Vector3d::Constant(s.margin));
        cell = std::min(cell, s.margin);
    }
    // At most 64 cells a side, however narrow the margins.
    cell = std::max(cell, (hi - lo).maxCoeff() / 64);
    if (!(cell > 0)) cell = 1;
    std::array<int, 3> count{};
    for (int a = 0; a < 3; ++a)
        count[a] = std::clamp(static_cast<int>(std::ceil((hi[a] - lo[a]) / cell)), 1, 64);
    const auto along = [&](int a, double x) {
        return std::clamp(static_cast<int>(std::floor((x - lo[a]) / cell)), 0, count[a] - 1);
    };
    const auto index = [&](int x, int y, int z) {
        return static_cast<std::size_t>((z * count[1] + y) * count[0] + x);
    };
    std::vector<std::vector<int>> in_cell(static_cast<std::size_t>(count[0] * count[1] * count[2]));
    for (std::size_t k = 0; k < seeds.size(); ++k) {
        const SeedToRegrow& s = seeds[k];
        std::array<int, 3> from{}, to{};
        for (int a = 0; a < 3; ++a) {
            from[a] = along(a, s.lo[a] - s.margin);
            to[a] = along(a, s.hi[a] + s.margin);
        }
        for (int z = from[2]; z <= to[2]; ++z)
            for (int y = from[1]; y <= to[1]; ++y)
                for (int x = from[0]; x <= to[0]; ++x)
                    in_cell[index(x, y, z)].push_back(static_cast<int>(k));
    }
    detail::parallel_for(static_cast<int>(positions.size()), [&](int v) {
        const Eigen::Vector3d& p = positions[v];
        if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) return;
        for (int k : in_cell[index(along(0, p[0]), along(1, p[1]), along(2, p[2]))])
            if (TileBoxes::distance(seeds[k].lo, seeds[k].hi, p) <= seeds[k].margin) {
                near[v] = 1;
                return;
            }
    });
    return near;
}

// The cut of `mesh` that `seeds` grow again in: the faces with a vertex near one of them
// (near_regrowth), their vertices complete where near and complete in `mesh` (`complete`, or
// every vertex when it is null). No vertex is owned: the caller flags the seeds.
MeshTile regrowth_cut(const Mesh& mesh, const std::vector<char>* complete,
                      const std::vector<SeedToRegrow>& seeds) {
    std::vector<char> near = near_regrowth(mesh.positions, seeds);
    std::vector<char> taken(mesh.faces.size(), 0);
    detail::parallel_for(mesh.num_faces(), [&](int f) {
        const auto& fv = mesh.faces[f];
        taken[f] = near[fv[0]] || near[fv[1]] || near[fv[2]] ? 1 : 0;
    });
    for (std::size_t v = 0; v < near.size(); ++v)  // gathered_tile's codes: 2 complete, 0 not
        near[v] = near[v] && (!complete || (*complete)[v]) ? 2 : 0;
    return detail::gathered_tile(mesh, near, taken);
}

// The depth map of `cut`, restricted from `whole`'s: its faces' depths made from its vertices'
// where `whole` has none (each face's mean of the same three depths in the same order, so the
// bits restriction would give).
DepthMap cut_depth_map(const DepthMap& whole, const MeshTile& cut) {
    DepthMap out;
    out.orientation = whole.orientation;
    out.vertex_depth = restricted(whole.vertex_depth, cut.vertex);
    if (whole.face_depth.empty())
        set_face_depths(cut.mesh, out);
    else
        out.face_depth = restricted(whole.face_depth, cut.face);
    return out;
}

}  // namespace

std::optional<TilePart> texel_part(const Mesh& mesh, const std::vector<const DepthMap*>& depth,
                                   const std::vector<double>& thresholds, const TexelParams& params,
                                   const TileBoxes& boxes, int b, double width, double max_width,
                                   MeshTile* mesh_tile,
                                   const std::function<Mesh()>& read_mesh_again) {
    // The regions of the seeds the tile owns grow first in a cut of its box with a halo `width`
    // wide. A region that grows onto a face whose neighbours the cut may not all hold could
    // have grown further in the whole mesh: its seed grows again in a cut around that region
    // alone, with twice the margin each time it reaches the edge of such a cut, until it is
    // whole (at worst the cut holds all of `mesh`). Such regions lie along the tile's edges,
    // each a small part of it: grown again in the whole tile, they made a texel job hold the
    // tile's topology, the largest table of the job.
    TilePart part;
    part.tile = b;
    part.thresholds = thresholds;
    const std::size_t n = depth.size();
    part.regions.resize(n);
    part.region_depths.resize(n);
    // A seed's discs (r, and 2r for its threshold) must lie whole in the first cut, or a region
    // grown there could be whole with another threshold than the whole mesh's.
    width = std::max(width, kTexelHaloRadii * params.radius);
    if (width > max_width) return std::nullopt;
    // The edge of `mesh` when it is a tile: a region that reaches it needs a wider tile.
    const bool in_tile = mesh_tile && &mesh == &mesh_tile->mesh;
    const std::vector<char>* complete = in_tile ? &mesh_tile->complete_vertex : nullptr;
    std::vector<std::vector<FinishedRegion>> finished(n);
    std::vector<std::vector<SeedToRegrow>> regrow(n);  // each orientation's, grown in one cut
    const double first_margin = width;                 // as wide as the seeds' discs want
    // The tile's mesh is let go while the regions grow in the first cut, when it can be read
    // again (a tile job): its positions and faces are most of what the job holds beside.
    const bool released = in_tile && read_mesh_again;
    {
        const MeshTile cut = make_mesh_tile(mesh, boxes, b, width);
        if (released) mesh_tile->mesh = Mesh();
        const MeshTopology topology = make_topology(cut.mesh);
        for (std::size_t i = 0; i < n; ++i) {
            if (cut.mesh.faces.empty()) continue;  // no seed, no region
            const DepthMap map = cut_depth_map(*depth[i], cut);
            TexelRegions grown = grow_texel_regions(cut.mesh, topology, map, params, thresholds[i],
                                                    cut.owned_vertex);
            part.regions[i].num_seeds = grown.num_seeds;
            for (TexelRegion& r : grown.regions) {
                if (region_whole(r, cut))
                    finished[i].push_back(finished_region(std::move(r), cut, map));
                else
                    regrow[i].push_back(regrowth_of(r, cut, first_margin));
            }
        }
    }
    const auto pending = [&] {
        std::vector<SeedToRegrow> all;
        for (const std::vector<SeedToRegrow>& r : regrow) all.insert(all.end(), r.begin(), r.end());
        return all;
    };
    std::vector<SeedToRegrow> all = pending();
    if (released && !all.empty()) {
        mesh_tile->mesh = read_mesh_again();  // `mesh` refers to it
        if (mesh_tile->mesh.positions.size() != mesh_tile->vertex.size() ||
            mesh_tile->mesh.faces.size() != mesh_tile->face.size())
            throw InvalidInput("tiles: tile " + std::to_string(b + 1) +
                               "'s mesh read again is not the one read first");
    }
    for (; !all.empty(); all = pending()) {
        const MeshTile cut = regrowth_cut(mesh, complete, all);
        all = std::vector<SeedToRegrow>();
        const MeshTopology topology = make_topology(cut.mesh);
        for (std::size_t i = 0; i < n; ++i) {
            if (regrow[i].empty()) continue;
            std::vector<char> seeds(cut.vertex.size(), 0);
            for (const SeedToRegrow& s : regrow[i]) {
                const int v = index_in(cut.vertex, s.seed);  // within its margin, so in the cut
                if (v < 0)
                    throw InvalidInput("tiles: tile " + std::to_string(b + 1) +
                                       ": a seed to grow again is not in the cut around it");
                seeds[static_cast<std::size_t>(v)] = 1;
            }
            const DepthMap map = cut_depth_map(*depth[i], cut);
            TexelRegions grown =
                grow_texel_regions(cut.mesh, topology, map, params, thresholds[i], seeds);
            // The seeds' discs lie in the cut, whole: each is found a seed again.
            if (grown.regions.size() != regrow[i].size())
                throw InvalidInput("tiles: tile " + std::to_string(b + 1) +
                                   ": a seed grown again is no longer a seed");
            std::vector<SeedToRegrow> again;
            for (TexelRegion& r : grown.regions) {
                if (region_whole(r, cut)) {
                    finished[i].push_back(finished_region(std::move(r), cut, map));
                    continue;
                }
                // A region that reaches the edge of the tile itself needs a wider tile.
                for (int f : r.faces)
                    for (int v : cut.mesh.faces[f])
                        if (complete && !(*complete)[static_cast<std::size_t>(cut.vertex[v])])
                            return std::nullopt;
                const int seed = cut.vertex[r.seed];
                const auto was =
                    std::find_if(regrow[i].begin(), regrow[i].end(),
                                 [&](const SeedToRegrow& s) { return s.seed == seed; });
                again.push_back(regrowth_of(r, cut, 2 * was->margin));
            }
            regrow[i] = std::move(again);
        }
    }
    // The order grow_texel_regions gives the tile's seeds: the deepest first, the lower id on
    // a tie (a cut numbers its vertices in the order of what it was cut from).
    for (std::size_t i = 0; i < n; ++i) {
        std::vector<FinishedRegion>& done = finished[i];
        std::sort(done.begin(), done.end(), [](const FinishedRegion& a, const FinishedRegion& c) {
            return a.seed_depth > c.seed_depth ||
                   (a.seed_depth == c.seed_depth && a.region.seed < c.region.seed);
        });
        RegionDepths& d = part.region_depths[i];
        for (FinishedRegion& f : done) {
            d.seed.push_back(f.seed_depth);
            d.face.insert(d.face.end(), f.face.begin(), f.face.end());
            d.peak.insert(d.peak.end(), f.peak.begin(), f.peak.end());
            f.face = std::vector<double>();  // not held twice while the part's lists grow
            f.peak = std::vector<double>();
            part.regions[i].regions.push_back(std::move(f.region));
        }
    }
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
