// DiscAverager: exact disc means, or exact means at sparse samples interpolated elsewhere.

#include "geometry/disc_means.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/union_find.hpp"
#include "geometry/neighbourhood.hpp"

namespace geotex {

namespace {

// Reach of the clusters of exactly averaged vertices, / r: larger clusters share one walk
// among more members but widen the ring each member filters (measured on sphere-1 level 7
// at 4%, disc_clusters.hpp).
constexpr double kClusterReach = 0.35;

struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
};

// Scratch buffers of a breadth-first walk over the patch graph.
struct Walk {
    std::vector<std::uint32_t> stamp;
    std::uint32_t generation = 0;
    std::vector<int> queue;
};

// Disc mean of `values` at a sample, and the unit weighted mean of the vertex normals over
// the same disc (the normal of the smoothed surface at the mean).
struct SampleMean {
    Eigen::Vector3d mean;
    Eigen::Vector3d normal;
    Eigen::Vector3d position;  // of the sample vertex: read beside the others by the interpolation
};

}  // namespace

DiscAverager::DiscAverager(const Mesh& mesh, const MeshTopology& topology,
                           const std::vector<double>& weight,
                           const std::vector<Eigen::Vector3d>& normal, const DiscMeanParams& params)
    : mesh_(&mesh),
      topology_(&topology),
      weight_(&weight),
      normal_(&normal),
      radius_(params.radius),
      exact_samples_(params.exact_samples) {
    const int nv = mesh.num_vertices();
    if (!(params.radius > 0) || !std::isfinite(params.radius))
        throw InvalidInput("disc means: the radius must be positive and finite (got " +
                           std::to_string(params.radius) + ")");
    if (static_cast<int>(weight.size()) != nv || static_cast<int>(normal.size()) != nv ||
        static_cast<int>(topology.vertex_neighbour_offsets.size()) != nv + 1)
        throw InvalidInput(
            "disc means: " + std::to_string(weight.size()) + " weights, " +
            std::to_string(normal.size()) + " normals and " +
            std::to_string(topology.vertex_neighbour_offsets.size()) + " topology offsets for " +
            std::to_string(nv) +
            " vertices; give one weight and normal per vertex and the mesh's topology");
    if (!(params.sample_spacing_rel > 0 && params.sample_spacing_rel <= 1))
        throw InvalidInput(
            "disc means: the sample spacing must be in (0, 1] times the radius (got " +
            std::to_string(params.sample_spacing_rel) + ")");
    if (!(params.support_rel >= 1.8) ||
        !((params.support_rel + std::sqrt(3.0)) * params.sample_spacing_rel <= 1))
        throw InvalidInput(
            "disc means: the interpolation radius must be at least 1.8 sample spacings and, with a "
            "cell diagonal, at most the disc radius: (h/s + sqrt 3) s/r <= 1 (got h/s = " +
            std::to_string(params.support_rel) +
            ", s/r = " + std::to_string(params.sample_spacing_rel) + ")");
    vertex_patch_.assign(nv, -1);
    std::vector<char> walked(nv, 1);
    setup_fast(params, walked);
    // The exact walks are bound by memory latency: walk a copy of the exact components laid
    // out along a space-filling curve (same discs, same order, same sums).
    if (std::find(walked.begin(), walked.end(), 1) == walked.end()) return;
    walk_graph_ = make_walk_graph(mesh, topology, walked);

    // Clusters of reach kClusterReach r (disc_clusters.hpp): each walk around one gives the
    // discs of its members (level 7 at 4%: 14 on average). Record them while the budget lasts.
    // Which clusters get recorded may depend on scheduling; the means do not, since a recorded
    // cluster is the walk's own.
    clusters_ = make_disc_clusters(walk_graph_, kClusterReach * radius_);
    const int nc = clusters_.num_clusters();
    recorded_.resize(nc);
    if (params.max_recorded_disc_vertices == 0) return;
    std::atomic<std::int64_t> budget{static_cast<std::int64_t>(std::min<std::size_t>(
        params.max_recorded_disc_vertices, std::numeric_limits<std::int64_t>::max()))};
    struct Recorder {
        ClusterDiscWalker walker;
        ClusterDiscs scratch;  // grown once per thread; each record is an exact-size copy
    };
    detail::parallel_for_with(
        nc,
        [&] {
            return Recorder{ClusterDiscWalker(walk_graph_), {}};
        },
        [&](int k, Recorder& r) {
            if (budget.load(std::memory_order_relaxed) <= 0) return;
            r.walker.walk(clusters_, k, radius_, r.scratch);
            recorded_[k] = r.scratch;
            budget.fetch_sub(static_cast<std::int64_t>(r.scratch.footprint()),
                             std::memory_order_relaxed);
        },
        8);
}

namespace {

// Cubic sampling cells of side `spacing` from the lowest corner of the bounding box.
struct SamplingGrid {
    Eigen::Vector3d lo;
    double spacing = 0;
    std::vector<Cell> cell;  // #V

    Eigen::Vector3d centre(const Cell& c) const {
        return lo + spacing * Eigen::Vector3d(static_cast<double>(c.x) + 0.5,
                                              static_cast<double>(c.y) + 0.5,
                                              static_cast<double>(c.z) + 0.5);
    }
};

// The cell of every vertex in `sampling`'s grid; none when it has too many cells per axis.
std::optional<SamplingGrid> make_sampling_grid(const std::vector<Eigen::Vector3d>& p,
                                               double spacing, const DiscSampling& sampling) {
    if (!sampling.grid) return std::nullopt;
    const Eigen::Vector3d lo = sampling.origin;
    SamplingGrid grid{lo, spacing, std::vector<Cell>(p.size())};
    detail::parallel_for(static_cast<int>(p.size()), [&](int v) {
        const Eigen::Vector3d q = (p[v] - lo) / spacing;
        grid.cell[v] = {static_cast<std::int64_t>(std::floor(q.x())),
                        static_cast<std::int64_t>(std::floor(q.y())),
                        static_cast<std::int64_t>(std::floor(q.z()))};
    });
    return grid;
}

struct Patches {
    std::vector<int> vertex_patch;   // #V: patch id, or -1 for a vertex not sampled
    std::vector<int> sample_vertex;  // #patches
};

// A patch is a piece of one cell connected by mesh edges, so a cell crossed by two sheets (or
// two components) holds two patches. Patch ids in the order of their smallest vertex; the
// sample of a patch is its vertex nearest the cell centre (the lowest index on a tie), so
// samples are about one cell apart.
Patches make_patches(const Mesh& mesh, const MeshTopology& topology, const std::vector<char>& fast,
                     const SamplingGrid& grid) {
    const int nv = mesh.num_vertices();
    const std::vector<Eigen::Vector3d>& p = mesh.positions;
    const std::vector<Cell>& cell = grid.cell;
    detail::UnionFind pieces(nv);
    for (int v = 0; v < nv; ++v) {
        if (!fast[v]) continue;
        for (int u : topology.neighbours(v))
            if (u > v && fast[u] && cell[u] == cell[v]) pieces.unite(u, v);
    }
    Patches out{std::vector<int>(nv, -1), {}};
    std::vector<double> centre_distance;
    for (int v = 0; v < nv; ++v) {
        if (!fast[v]) continue;
        const int root = pieces.find(v);
        const double d = (p[v] - grid.centre(cell[v])).squaredNorm();
        if (root == v) {
            out.vertex_patch[v] = static_cast<int>(out.sample_vertex.size());
            out.sample_vertex.push_back(v);
            centre_distance.push_back(d);
        } else {
            const int id = out.vertex_patch[root];
            out.vertex_patch[v] = id;
            if (d < centre_distance[id]) {
                centre_distance[id] = d;
                out.sample_vertex[id] = v;
            }
        }
    }
    return out;
}

// What the disc walk needs to know of each patch.
struct PatchShapes {
    std::vector<double> radius;               // farthest vertex of the patch from its sample
    std::vector<Eigen::Vector3d> centroid;    // mean vertex position
    std::vector<Eigen::Vector3d> normal_sum;  // sum of weight x normal
    std::vector<double> reach;                // farthest vertex from the centroid
    std::vector<double> spread;               // sqrt(2) x RMS distance to the centroid
};

PatchShapes measure_patches(const std::vector<Eigen::Vector3d>& p, const Patches& patches,
                            const std::vector<double>& weight,
                            const std::vector<Eigen::Vector3d>& normal) {
    const int nv = static_cast<int>(p.size());
    const int np = static_cast<int>(patches.sample_vertex.size());
    const std::vector<int>& vertex_patch = patches.vertex_patch;
    PatchShapes out;
    out.radius.assign(np, 0.0);
    out.centroid.assign(np, Eigen::Vector3d::Zero());
    out.normal_sum.assign(np, Eigen::Vector3d::Zero());
    out.reach.assign(np, 0.0);
    out.spread.assign(np, 0.0);
    std::vector<int> patch_size(np, 0);
    for (int v = 0; v < nv; ++v) {
        const int q = vertex_patch[v];
        if (q < 0) continue;
        out.radius[q] = std::max(out.radius[q], (p[v] - p[patches.sample_vertex[q]]).norm());
        out.centroid[q] += p[v];
        out.normal_sum[q] += weight[v] * normal[v];
        ++patch_size[q];
    }
    for (int q = 0; q < np; ++q) out.centroid[q] /= patch_size[q];
    for (int v = 0; v < nv; ++v) {
        const int q = vertex_patch[v];
        if (q < 0) continue;
        const double d2 = (p[v] - out.centroid[q]).squaredNorm();
        out.reach[q] = std::max(out.reach[q], std::sqrt(d2));
        out.spread[q] += d2;
    }
    for (int q = 0; q < np; ++q) out.spread[q] = std::sqrt(2 * out.spread[q] / patch_size[q]);
    return out;
}

// Rows of indices, compressed: row i is values[offsets[i], offsets[i + 1]).
struct CompressedRows {
    std::vector<int> offsets;
    std::vector<int> values;
};

// The patch graph: patches joined by a mesh edge, each row sorted.
CompressedRows link_patches(const MeshTopology& topology, const std::vector<int>& vertex_patch,
                            int np) {
    const int nv = static_cast<int>(vertex_patch.size());
    std::vector<std::pair<int, int>> links;
    for (int v = 0; v < nv; ++v) {
        if (vertex_patch[v] < 0) continue;
        for (int u : topology.neighbours(v))
            if (u > v && vertex_patch[u] >= 0 && vertex_patch[u] != vertex_patch[v]) {
                links.emplace_back(vertex_patch[v], vertex_patch[u]);
                links.emplace_back(vertex_patch[u], vertex_patch[v]);
            }
    }
    std::sort(links.begin(), links.end());
    links.erase(std::unique(links.begin(), links.end()), links.end());
    CompressedRows out{std::vector<int>(np + 1, 0), std::vector<int>(links.size())};
    for (const auto& l : links) ++out.offsets[l.first + 1];
    for (int i = 0; i < np; ++i) out.offsets[i + 1] += out.offsets[i];
    for (std::size_t k = 0; k < links.size(); ++k) out.values[k] = links[k].second;
    return out;
}

// The disc of every sample as fractions of patches, and the candidates of every patch.
struct SampleDiscs {
    std::vector<int> disc_offsets;  // #patches + 1
    std::vector<int> disc_patches;
    std::vector<double> disc_fractions;
    CompressedRows candidates;  // per patch, sorted
};

// The disc of each sample as fractions of patches: a patch inside the ball counts whole, one
// across its sphere (of radius sqrt(r^2 - a^2), see below) by the fraction of a disc of its
// spread (sqrt(2) x its RMS radius) on the inner side of a line at the centroid's distance.
// The patches are reached through the patch graph from the sample's own, so the disc never
// jumps a gap. Cost per sample: the patches of a disc, about 1.3 pi (r/s)^2, whatever the
// mesh resolution.
//
// The same walk collects the candidates of the patch P: the samples a vertex of P may find
// within h. Such a vertex is within rho_P (the patch radius, <= sqrt(3) s: one cell) of P's
// sample, so a candidate's sample is within h + rho_P <= (h/s + sqrt(3)) s <= r of it, inside
// the disc walked.
SampleDiscs walk_sample_discs(const std::vector<Eigen::Vector3d>& p,
                              const std::vector<int>& sample_vertex, const PatchShapes& shape,
                              const CompressedRows& links, double radius, double support) {
    const int np = static_cast<int>(sample_vertex.size());
    std::vector<std::vector<std::pair<int, double>>> discs(np);
    std::vector<std::vector<int>> lists(np);
    detail::parallel_for_with(
        np,
        [&] {
            return Walk{std::vector<std::uint32_t>(np, 0), 0, {}};
        },
        [&](int patch, Walk& w) {
            ++w.generation;
            const Eigen::Vector3d& centre = p[sample_vertex[patch]];
            w.queue.clear();
            w.queue.push_back(patch);
            w.stamp[patch] = w.generation;
            auto& disc = discs[patch];
            const double keep = support + shape.radius[patch], keep2 = keep * keep;
            std::vector<int>& list = lists[patch];
            for (std::size_t head = 0; head < w.queue.size(); ++head) {
                const int q = w.queue[head];
                if ((p[sample_vertex[q]] - centre).squaredNorm() < keep2) list.push_back(q);
                const double d2 = (shape.centroid[q] - centre).squaredNorm();
                const double inner = std::max(0.0, radius - shape.reach[q]);
                double f = 1;
                if (d2 > inner * inner) {
                    const double d = std::sqrt(d2);
                    const double a = shape.spread[q];
                    // The soft edge spreads the disc's second moment by a^2/2 per unit area
                    // (the spread of a disc of radius a); a sphere of radius sqrt(r^2 - a^2)
                    // gives back r^2/2, so the mean's shrinkage on a curved surface is kept.
                    const double rq = std::sqrt(std::max(0.0, radius * radius - a * a));
                    const double t =
                        a > 0 ? std::clamp((rq - d) / a, -1.0, 1.0) : (d <= radius ? 1.0 : -1.0);
                    f = 0.5 + (t * std::sqrt(1 - t * t) + std::asin(t)) / kPi;
                }
                if (f > 0) disc.emplace_back(q, f);
                for (int k = links.offsets[q]; k < links.offsets[q + 1]; ++k) {
                    const int t = links.values[k];
                    if (w.stamp[t] == w.generation) continue;
                    w.stamp[t] = w.generation;
                    const double reach = radius + shape.reach[t];
                    if ((shape.centroid[t] - centre).squaredNorm() < reach * reach)
                        w.queue.push_back(t);
                }
            }
        },
        16);
    SampleDiscs out;
    out.disc_offsets.assign(np + 1, 0);
    for (int i = 0; i < np; ++i)
        out.disc_offsets[i + 1] = out.disc_offsets[i] + static_cast<int>(discs[i].size());
    out.disc_patches.resize(out.disc_offsets[np]);
    out.disc_fractions.resize(out.disc_offsets[np]);
    for (int i = 0; i < np; ++i) {
        for (std::size_t k = 0; k < discs[i].size(); ++k) {
            out.disc_patches[out.disc_offsets[i] + k] = discs[i][k].first;
            out.disc_fractions[out.disc_offsets[i] + k] = discs[i][k].second;
        }
        std::vector<std::pair<int, double>>().swap(discs[i]);
    }
    CompressedRows& c = out.candidates;
    c.offsets.assign(np + 1, 0);
    for (int i = 0; i < np; ++i) {
        std::sort(lists[i].begin(), lists[i].end());
        c.offsets[i + 1] = c.offsets[i] + static_cast<int>(lists[i].size());
    }
    c.values.resize(c.offsets[np]);
    for (int i = 0; i < np; ++i) {
        std::copy(lists[i].begin(), lists[i].end(), c.values.begin() + c.offsets[i]);
        std::vector<int>().swap(lists[i]);
    }
    return out;
}

// A vertex with no sample strictly inside h (possible only with odd cells) is averaged
// exactly: its patch becomes -1.
void unsample_uncovered(const std::vector<Eigen::Vector3d>& p,
                        const std::vector<int>& sample_vertex, const CompressedRows& candidates,
                        double support, std::vector<int>& vertex_patch) {
    const double h2 = support * support;
    detail::parallel_for(static_cast<int>(vertex_patch.size()), [&](int v) {
        const int patch = vertex_patch[v];
        if (patch < 0) return;
        for (int k = candidates.offsets[patch]; k < candidates.offsets[patch + 1]; ++k)
            if ((p[sample_vertex[candidates.values[k]]] - p[v]).squaredNorm() < h2) return;
        vertex_patch[v] = -1;
    });
}

}  // namespace

void DiscAverager::setup_fast(const DiscMeanParams& params, std::vector<char>& walked) {
    const Mesh& mesh = *mesh_;
    const std::vector<Eigen::Vector3d>& p = mesh.positions;
    if (params.mode == DiscMode::Exact || mesh.num_vertices() == 0) return;
    std::optional<DiscSampling> own;
    if (!params.sampling) own = make_disc_sampling(mesh, params);
    const DiscSampling& sampling = params.sampling ? *params.sampling : *own;
    if (static_cast<int>(sampling.fast.size()) != mesh.num_vertices())
        throw InvalidInput("disc means: the sampling has " + std::to_string(sampling.fast.size()) +
                           " vertex flags for " + std::to_string(mesh.num_vertices()) +
                           " vertices");
    const std::vector<char>& fast = sampling.fast;
    for (std::size_t v = 0; v < fast.size(); ++v)
        if (fast[v]) walked[v] = 0;
    if (std::find(fast.begin(), fast.end(), 1) == fast.end()) return;  // every disc exact

    const double s = params.sample_spacing_rel * params.radius;
    support_ = params.support_rel * s;
    Patches patches;
    {
        // The vertices' cells (24 bytes a vertex) make the patches and are let go before the
        // samples' discs are walked, the largest step of the setup.
        const std::optional<SamplingGrid> grid = make_sampling_grid(p, s, sampling);
        if (!grid) return;
        patches = make_patches(mesh, *topology_, fast, *grid);
    }
    const int np = static_cast<int>(patches.sample_vertex.size());
    if (np == 0) return;
    const PatchShapes shape = measure_patches(p, patches, *weight_, *normal_);
    vertex_patch_ = std::move(patches.vertex_patch);
    sample_vertex_ = std::move(patches.sample_vertex);
    patch_normal_sum_ = shape.normal_sum;
    SampleDiscs discs = walk_sample_discs(
        p, sample_vertex_, shape, link_patches(*topology_, vertex_patch_, np), radius_, support_);
    unsample_uncovered(p, sample_vertex_, discs.candidates, support_, vertex_patch_);
    disc_offsets_ = std::move(discs.disc_offsets);
    disc_patches_ = std::move(discs.disc_patches);
    disc_fractions_ = std::move(discs.disc_fractions);
    candidate_offsets_ = std::move(discs.candidates.offsets);
    candidates_ = std::move(discs.candidates.values);
    num_interpolated_ = static_cast<int>(
        std::count_if(vertex_patch_.begin(), vertex_patch_.end(), [](int q) { return q >= 0; }));
}

std::vector<Eigen::Vector3d> DiscAverager::means(const std::vector<Eigen::Vector3d>& values) const {
    return means(values, *weight_);
}

std::vector<Eigen::Vector3d> DiscAverager::means(const std::vector<Eigen::Vector3d>& values,
                                                 const std::vector<double>& weight) const {
    const Mesh& mesh = *mesh_;
    const int nv = mesh.num_vertices();
    if (static_cast<int>(values.size()) != nv || static_cast<int>(weight.size()) != nv)
        throw InvalidInput("disc means: " + std::to_string(values.size()) + " values and " +
                           std::to_string(weight.size()) + " weights for " + std::to_string(nv) +
                           " vertices");
    const std::vector<Eigen::Vector3d>& normal = *normal_;
    const std::vector<Eigen::Vector3d>& p = mesh.positions;
    auto make_walker = [&] { return DiscWalker(mesh, *topology_); };

    // Patch sums of the values.
    const int np = num_samples();
    std::vector<double> patch_weight(np, 0.0);
    std::vector<Eigen::Vector3d> patch_value(np, Eigen::Vector3d::Zero());
    for (int v = 0; v < nv; ++v) {
        const int q = vertex_patch_[v];
        if (q < 0) continue;
        patch_weight[q] += weight[v];
        patch_value[q] += weight[v] * values[v];
    }
    // Disc means at the samples: walked exactly, or from the patch sums and the fractions
    // found at setup.
    std::vector<SampleMean> sample(np);
    if (exact_samples_) {
        detail::parallel_for_with(
            np, make_walker,
            [&](int i, DiscWalker& walker) {
                const int c = sample_vertex_[i];
                sample[i].position = p[c];
                Eigen::Vector3d sum = Eigen::Vector3d::Zero(), nsum = Eigen::Vector3d::Zero();
                double total = 0;
                for (int u : walker.disc(c, radius_)) {
                    sum += weight[u] * values[u];
                    nsum +=
                        (*weight_)[u] * normal[u];  // the surface's normal, whatever is left out
                    total += weight[u];
                }
                sample[i].mean = total > 0 ? Eigen::Vector3d(sum / total) : values[c];
                const double len = nsum.norm();
                sample[i].normal = len > 0 ? Eigen::Vector3d(nsum / len) : normal[c];
            },
            16);
    } else
        detail::parallel_for(
            np,
            [&](int i) {
                Eigen::Vector3d sum = Eigen::Vector3d::Zero(), nsum = Eigen::Vector3d::Zero();
                double total = 0;
                for (int k = disc_offsets_[i]; k < disc_offsets_[i + 1]; ++k) {
                    const int q = disc_patches_[k];
                    const double f = disc_fractions_[k];
                    sum += f * patch_value[q];
                    nsum += f * patch_normal_sum_[q];
                    total += f * patch_weight[q];
                }
                const int c = sample_vertex_[i];
                sample[i].position = p[c];
                sample[i].mean = total > 0 ? Eigen::Vector3d(sum / total) : values[c];
                const double len = nsum.norm();
                sample[i].normal = len > 0 ? Eigen::Vector3d(nsum / len) : normal[c];
            },
            64);

    std::vector<Eigen::Vector3d> out(nv);
    const int ng = walk_graph_.num_vertices();
    if (ng > 0) {
        // Exact components, walked in graph order over values in graph order.
        const std::vector<int>& mesh_vertex = walk_graph_.mesh_vertex;
        std::vector<double> graph_weight(ng);
        std::vector<Eigen::Vector3d> graph_value(ng);
        detail::parallel_for(ng, [&](int i) {
            graph_weight[i] = weight[mesh_vertex[i]];
            graph_value[i] = values[mesh_vertex[i]];
        });
        // Each member's sum starts from its cluster's core sum, then adds its part of the
        // ring in ring order; a member walked alone sums its own disc.
        struct Scratch {
            ClusterDiscWalker walker;
            ClusterDiscs discs;
            std::vector<double> ring_weight;  // the ring's terms, read by every member
            std::vector<Eigen::Vector3d> ring_term;
        };
        detail::parallel_for_with(
            clusters_.num_clusters(),
            [&] {
                return Scratch{ClusterDiscWalker(walk_graph_), {}, {}, {}};
            },
            [&](int k, Scratch& scratch) {
                const ClusterDiscs* cd = &recorded_[k];
                if (cd->core.empty()) {
                    scratch.walker.walk(clusters_, k, radius_, scratch.discs);
                    cd = &scratch.discs;
                }
                Eigen::Vector3d core_sum = Eigen::Vector3d::Zero();
                double core_total = 0;
                for (int u : cd->core) {
                    core_sum += graph_weight[u] * graph_value[u];
                    core_total += graph_weight[u];
                }
                const int nr = static_cast<int>(cd->ring.size());
                scratch.ring_weight.resize(nr);
                scratch.ring_term.resize(nr);
                for (int j = 0; j < nr; ++j) {
                    const int u = cd->ring[j];
                    scratch.ring_weight[j] = graph_weight[u];
                    scratch.ring_term[j] = graph_weight[u] * graph_value[u];
                }
                const int* member = clusters_.members.data() + clusters_.offsets[k];
                for (int i = 0; i < clusters_.size(k); ++i) {
                    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
                    double total = 0;
                    if (cd->has_own(i)) {
                        for (int u : cd->own_disc(i)) {
                            sum += graph_weight[u] * graph_value[u];
                            total += graph_weight[u];
                        }
                    } else {
                        sum = core_sum;
                        total = core_total;
                        const std::uint64_t* mask = cd->mask(i);
                        for (int w = 0; w < cd->words; ++w)
                            for (std::uint64_t bits = mask[w]; bits != 0; bits &= bits - 1) {
                                const int j = 64 * w + __builtin_ctzll(bits);
                                sum += scratch.ring_term[j];
                                total += scratch.ring_weight[j];
                            }
                    }
                    const int v = member[i];
                    out[mesh_vertex[v]] = total > 0 ? Eigen::Vector3d(sum / total) : graph_value[v];
                }
            },
            4);
        if (ng == nv) return out;
    }
    const double h2 = support_ * support_;
    detail::parallel_for_with(nv, make_walker, [&](int v, DiscWalker& walker) {
        const int patch = vertex_patch_[v];
        if (patch < 0) {
            if (ng > 0 && walk_graph_.graph_vertex[v] >= 0) return;  // done above
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            double total = 0;
            for (int u : walker.disc(v, radius_)) {
                sum += weight[u] * values[u];
                total += weight[u];
            }
            out[v] = total > 0 ? Eigen::Vector3d(sum / total) : values[v];
            return;
        }
        // Each sample's estimate of M(v): its mean moved along its tangent plane by the
        // tangential offset x of v (x . n_c = 0), then along n_c by the smoothed surface's
        // curvature, read from the change of normal: height = (n_c - n_v) . x / 2 = -n_v . x / 2
        // (exact to second order).
        // Linear precision: on a plane the estimate is M(c) + (v - c). The term in the
        // smoothed normal n_v (the weighted mean of the sample normals) is summed as the
        // matrix sum w n_c x^T, so that one pass over the samples suffices.
        const int first = candidate_offsets_[patch], last = candidate_offsets_[patch + 1];
        Eigen::Vector3d sum = Eigen::Vector3d::Zero(), n_v = Eigen::Vector3d::Zero();
        Eigen::Matrix3d bend = Eigen::Matrix3d::Zero();
        double total = 0;
        for (int k = first; k < last; ++k) {
            const int i = candidates_[k];
            const Eigen::Vector3d e = p[v] - sample[i].position;
            const double d2 = e.squaredNorm();
            if (d2 >= h2) continue;
            const double a = 1 - d2 / h2, w = a * a;
            const Eigen::Vector3d& n_c = sample[i].normal;
            const Eigen::Vector3d x = e - e.dot(n_c) * n_c;
            sum += w * (sample[i].mean + x);
            bend += w * n_c * x.transpose();
            n_v += w * n_c;
            total += w;
        }
        if (n_v.squaredNorm() > 0) n_v.normalize();
        sum -= 0.5 * bend * n_v;
        out[v] = sum / total;
    });
    return out;
}

}  // namespace geotex
