#include "geometry/texels.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "common/errors.hpp"
#include "common/release.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/union_find.hpp"
#include "geometry/neighbourhood.hpp"
#include "geometry/otsu.hpp"

namespace geotex {

namespace {

struct Region {
    std::vector<int> faces;  // sorted
    int seed = -1;
    double threshold = 0;
    double mean = 0, std = 0;
};

// Mean and population standard deviation of the depths of `faces`.
std::pair<double, double> depth_stats(const std::vector<int>& faces,
                                      const std::vector<double>& fd) {
    if (faces.empty()) return {0.0, 0.0};
    double sum = 0;
    for (int f : faces) sum += fd[f];
    const double mean = sum / static_cast<double>(faces.size());
    double sq = 0;
    for (int f : faces) sq += (fd[f] - mean) * (fd[f] - mean);
    return {mean, std::sqrt(sq / static_cast<double>(faces.size()))};
}

// Scratch buffers of one thread for growing regions.
struct RegionWorkspace {
    DiscWalker walker;
    std::vector<std::uint32_t> face_stamp;
    std::uint32_t generation = 0;
    std::vector<double> local_depths;
    std::vector<int> queue;
};

// Local region of one seed (paper §3.2): Otsu threshold over the faces of the 2r disc,
// then the face-connected component of the seed's faces whose depth reaches it.
Region grow_region(int seed, const Mesh& mesh, const MeshTopology& topology, const DepthMap& depth,
                   double radius, double floor, RegionWorkspace& ws) {
    Region region;
    region.seed = seed;
    const auto& disc = ws.walker.disc(seed, 2 * radius);
    ws.local_depths.clear();
    for (int u : disc)
        for (int f : topology.faces_of(u)) {
            const auto& fv = mesh.faces[f];
            const int smallest = std::min({fv[0], fv[1], fv[2]});
            // Count each face once, from its smallest vertex, and only when it lies inside.
            if (smallest == u && ws.walker.contains(fv[0]) && ws.walker.contains(fv[1]) &&
                ws.walker.contains(fv[2]))
                ws.local_depths.push_back(depth.face_depth[f]);
        }
    const OtsuResult otsu = otsu_threshold(ws.local_depths);
    if (!otsu.split) return region;
    region.threshold = std::max(otsu.threshold, floor);

    if (++ws.generation == 0) {
        std::fill(ws.face_stamp.begin(), ws.face_stamp.end(), 0u);
        ws.generation = 1;
    }
    ws.queue.clear();
    for (int f : topology.faces_of(seed))
        if (depth.face_depth[f] >= region.threshold && ws.face_stamp[f] != ws.generation) {
            ws.face_stamp[f] = ws.generation;
            ws.queue.push_back(f);
        }
    for (std::size_t head = 0; head < ws.queue.size(); ++head)
        for (int g : topology.face_neighbours_of(ws.queue[head]))
            if (ws.face_stamp[g] != ws.generation && depth.face_depth[g] >= region.threshold) {
                ws.face_stamp[g] = ws.generation;
                ws.queue.push_back(g);
            }
    region.faces = ws.queue;
    std::sort(region.faces.begin(), region.faces.end());
    std::tie(region.mean, region.std) = depth_stats(region.faces, depth.face_depth);
    return region;
}

}  // namespace

double depth_interval_overlap(double mu_a, double sigma_a, double mu_b, double sigma_b) {
    const double lo_a = mu_a - sigma_a, hi_a = mu_a + sigma_a;
    const double lo_b = mu_b - sigma_b, hi_b = mu_b + sigma_b;
    const double narrow = std::min(hi_a - lo_a, hi_b - lo_b);
    if (!(narrow > 0)) {  // a point: inside the other closed interval or not
        const bool a_is_point = hi_a - lo_a <= hi_b - lo_b;
        const double point = a_is_point ? mu_a : mu_b;
        const double lo = a_is_point ? lo_b : lo_a, hi = a_is_point ? hi_b : hi_a;
        return point >= lo && point <= hi ? 1.0 : 0.0;
    }
    const double overlap = std::min(hi_a, hi_b) - std::max(lo_a, lo_b);
    return std::max(0.0, overlap) / narrow;
}

namespace {

void check_inputs(const Mesh& mesh, const MeshTopology& topology, const DepthMap& depth,
                  const TexelParams& params) {
    const int nv = mesh.num_vertices();
    const int nf = mesh.num_faces();
    // The regions walk the faces' neighbours, which a topology may be made without.
    if (topology.vertex_neighbour_offsets.size() != mesh.positions.size() + 1 ||
        topology.face_neighbour_offsets.size() != mesh.faces.size() + 1)
        throw InvalidInput(
            "texels: the topology does not match the mesh, or has no faces' neighbours");
    if (!(params.radius > 0) || !std::isfinite(params.radius))
        throw InvalidInput("texels: the radius must be positive and finite (got " +
                           std::to_string(params.radius) + ")");
    if (static_cast<int>(depth.vertex_depth.size()) != nv ||
        static_cast<int>(depth.face_depth.size()) != nf)
        throw InvalidInput("texels: the depth map does not match the mesh (" +
                           std::to_string(depth.vertex_depth.size()) + " vertex depths for " +
                           std::to_string(nv) + " vertices)");
    if (!(params.merge_overlap >= 0 && params.merge_overlap <= 1))
        throw InvalidInput("texels: merge_overlap must be in [0, 1]");
}

// Seeds and their regions (§3.2.1-2), deepest seed first; `touch` lists are filled when asked.
TexelRegions grow_regions(const Mesh& mesh, const MeshTopology& topology, const DepthMap& depth,
                          const TexelParams& params, double global_threshold,
                          const std::vector<char>& seed_vertices, bool with_touch) {
    const int nf = mesh.num_faces();
    const double floor = params.min_depth_rel * params.radius;
    const auto& vd = depth.vertex_depth;
    std::vector<int> candidates;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (vd[v] >= global_threshold && vd[v] > 0 && (seed_vertices.empty() || seed_vertices[v]))
            candidates.push_back(v);

    // Seeds: strict local maxima over N_r; equal depths are ordered by vertex index so that
    // a plateau still yields exactly one seed.
    auto deeper = [&](int a, int b) { return vd[a] > vd[b] || (vd[a] == vd[b] && a < b); };
    std::vector<char> is_seed(candidates.size(), 0);
    detail::parallel_for_with(
        static_cast<int>(candidates.size()), [&] { return DiscWalker(mesh, topology); },
        [&](int i, DiscWalker& walker) {
            // Most candidates have a deeper vertex in their first ring: stop the walk there
            // rather than walking the whole disc (O(candidates x |N_r|) on fine meshes).
            const int v = candidates[i];
            is_seed[i] = walker.find_in_disc(v, params.radius,
                                             [&](int u) { return u != v && deeper(u, v); }) < 0;
        },
        16);
    std::vector<int> seeds;
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (is_seed[i]) seeds.push_back(candidates[i]);
    std::sort(seeds.begin(), seeds.end(), deeper);

    // One local region per seed, in parallel (each writes its own slot).
    TexelRegions out;
    out.num_seeds = static_cast<int>(seeds.size());
    out.regions.resize(seeds.size());
    detail::parallel_for_with(
        static_cast<int>(seeds.size()),
        [&] {
            return RegionWorkspace{
                DiscWalker(mesh, topology), std::vector<std::uint32_t>(nf, 0u), 0u, {}, {}};
        },
        [&](int i, RegionWorkspace& ws) {
            Region grown = grow_region(seeds[i], mesh, topology, depth, params.radius, floor, ws);
            TexelRegion& r = out.regions[i];
            r.seed = seeds[i];
            r.threshold = grown.threshold;
            r.mean = grown.mean;
            r.std = grown.std;
            r.faces = std::move(grown.faces);
            if (with_touch && !r.faces.empty()) {
                r.touch = r.faces;
                for (int f : r.faces)
                    for (int g : topology.face_neighbours_of(f)) r.touch.push_back(g);
                std::sort(r.touch.begin(), r.touch.end());
                r.touch.erase(std::unique(r.touch.begin(), r.touch.end()), r.touch.end());
            }
        },
        4);
    return out;
}

// Merging and face assignment (§3.2.3) of regions deepest seed first over `nf` faces with
// depths `fd`; `touch(i, visit)` calls visit on every face of region i and every face next to
// one, repeats allowed. The regions' face and touch lists are released once the candidate
// pairs are found, and each array once the next step has read it, so that a tiled run's join,
// which merges every region of a large scan, holds few of them at a time.
template <class Touch>
TexelSet merge_regions(std::vector<TexelRegion>& regions, int num_seeds, int nf,
                       const std::vector<double>& fd, const TexelParams& params,
                       DetailOrientation orientation, double global_threshold, Touch&& touch) {
    TexelSet out;
    out.global_threshold = global_threshold;
    out.num_local_maxima = num_seeds;
    int num_empty = 0;
    for (const auto& r : regions) num_empty += r.faces.empty() ? 1 : 0;
    out.num_regions = static_cast<int>(regions.size()) - num_empty;
    if (num_empty > 0)
        out.diagnostics.push_back({"texels", std::to_string(num_empty) +
                                                 " seeds gave no region (no face around the seed "
                                                 "reaches its local threshold)"});

    // Which regions claim each face (compressed rows; region indices ascending).
    const int nr = static_cast<int>(regions.size());
    std::vector<int> claim_offsets(nf + 1, 0);
    for (const auto& r : regions)
        for (int f : r.faces) ++claim_offsets[f + 1];
    for (int f = 0; f < nf; ++f) claim_offsets[f + 1] += claim_offsets[f];
    std::vector<int> claims(claim_offsets[nf]);
    {
        std::vector<int> fill(claim_offsets.begin(), claim_offsets.end() - 1);
        for (int i = 0; i < nr; ++i)
            for (int f : regions[i].faces) claims[fill[f]++] = i;
    }

    // Candidate pairs: a shared face, or a face of one next to a face of the other. Each pair
    // is listed once: where large regions overlap (a CAD part's flat faces, a scan's broad
    // swellings) a face has many claimants, and listing a pair once per face that shows it
    // made this step cost the square of the overlap.
    std::vector<std::pair<int, int>> pairs;
    std::vector<int> paired_with(nr, -1);  // the last region i that listed (i, j)
    for (int i = 0; i < nr; ++i)
        touch(i, [&](int g) {
            for (int k = claim_offsets[g]; k < claim_offsets[g + 1]; ++k) {
                const int j = claims[k];
                if (j > i && paired_with[j] != i) {
                    paired_with[j] = i;
                    pairs.emplace_back(i, j);
                }
            }
        });
    std::sort(pairs.begin(), pairs.end());
    release(paired_with);
    for (TexelRegion& r : regions) {
        release(r.faces);
        release(r.touch);
    }

    detail::UnionFind merged(nr);  // root = region of the deepest seed (seeds are sorted by depth)
    for (const auto& [a, b] : pairs) {
        const double overlap = depth_interval_overlap(regions[a].mean, regions[a].std,
                                                      regions[b].mean, regions[b].std);
        if (overlap >= params.merge_overlap && merged.unite(a, b)) ++out.num_merges;
    }

    // Each claimed face goes to the group of the deepest seed among its claimants.
    std::vector<int> face_group(nf, -1);
    for (int f = 0; f < nf; ++f)
        if (claim_offsets[f] < claim_offsets[f + 1])
            face_group[f] = merged.find(claims[claim_offsets[f]]);
    release(claims);
    release(claim_offsets);
    std::vector<std::vector<int>> group_faces(nr);
    for (int f = 0; f < nf; ++f)
        if (face_group[f] >= 0) group_faces[face_group[f]].push_back(f);  // ascending
    release(face_group);

    int num_small = 0;
    std::vector<int> groups;
    for (int g = 0; g < nr; ++g) {
        if (group_faces[g].empty()) continue;
        if (static_cast<int>(group_faces[g].size()) < params.min_faces) {
            ++num_small;
            continue;
        }
        groups.push_back(g);
    }
    if (num_small > 0)
        out.diagnostics.push_back({"texels", "dropped " + std::to_string(num_small) +
                                                 " regions smaller than " +
                                                 std::to_string(params.min_faces) + " faces"});
    std::sort(groups.begin(), groups.end(),
              [&](int a, int b) { return group_faces[a].front() < group_faces[b].front(); });
    out.face_texel.assign(nf, -1);
    for (int g : groups) {
        Texel t;
        t.faces = std::move(group_faces[g]);
        t.seed = regions[g].seed;
        t.orientation = orientation;
        t.threshold = regions[g].threshold;
        std::tie(t.depth_mean, t.depth_std) = depth_stats(t.faces, fd);
        const int id = static_cast<int>(out.texels.size());
        for (int f : t.faces) out.face_texel[f] = id;
        out.texels.push_back(std::move(t));
    }
    return out;
}

}  // namespace

double texel_global_threshold(std::vector<double> vertex_depth, const TexelParams& params) {
    return texel_global_threshold(otsu_threshold(std::move(vertex_depth)), params);
}

double texel_global_threshold(const OtsuResult& otsu, const TexelParams& params) {
    // Global Otsu over the whole depth map keeps the seeds of the salient part (§3.2.1).
    return std::max(otsu.threshold, params.min_depth_rel * params.radius);
}

TexelRegions grow_texel_regions(const Mesh& mesh, const MeshTopology& topology,
                                const DepthMap& depth, const TexelParams& params,
                                double global_threshold, const std::vector<char>& seed_vertices) {
    check_inputs(mesh, topology, depth, params);
    if (!seed_vertices.empty() && static_cast<int>(seed_vertices.size()) != mesh.num_vertices())
        throw InvalidInput("texels: the seed flags do not match the mesh");
    return grow_regions(mesh, topology, depth, params, global_threshold, seed_vertices, true);
}

TexelSet merge_texel_regions(TexelRegions regions, const std::vector<double>& face_depth,
                             const TexelParams& params, DetailOrientation orientation,
                             double global_threshold) {
    const int nf = static_cast<int>(face_depth.size());
    for (const TexelRegion& r : regions.regions)
        for (const std::vector<int>* ids : {&r.faces, &r.touch})
            for (int f : *ids)
                if (f < 0 || f >= nf)
                    throw InvalidInput("texels: a region's face is not below the face count");
    return merge_regions(regions.regions, regions.num_seeds, nf, face_depth, params, orientation,
                         global_threshold, [&](int i, auto&& visit) {
                             for (int f : regions.regions[i].faces) visit(f);
                             for (int f : regions.regions[i].touch) visit(f);
                         });
}

TexelSet make_texels(const Mesh& mesh, const MeshTopology& topology, const DepthMap& depth,
                     const TexelParams& params) {
    check_inputs(mesh, topology, depth, params);
    const double global_threshold = texel_global_threshold(depth.vertex_depth, params);
    TexelRegions grown = grow_regions(mesh, topology, depth, params, global_threshold, {}, false);
    return merge_regions(grown.regions, grown.num_seeds, mesh.num_faces(), depth.face_depth, params,
                         depth.orientation, global_threshold, [&](int i, auto&& visit) {
                             for (int f : grown.regions[i].faces) {
                                 visit(f);
                                 for (int g : topology.face_neighbours_of(f)) visit(g);
                             }
                         });
}

}  // namespace geotex
