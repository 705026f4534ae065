#include "geometry/rims.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <string>
#include <tuple>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"

namespace geotex {

std::vector<double> texel_depths(const Mesh& mesh, const TexelSet& set, const DepthMap& depth) {
    std::vector<double> out(set.texels.size(), 0.0);
    for (std::size_t t = 0; t < set.texels.size(); ++t)
        for (int f : set.texels[t].faces)
            for (int v : mesh.faces[f]) out[t] = std::max(out[t], depth.vertex_depth[v]);
    return out;
}

namespace {

// Shortest edge-path distances from a set of vertices, up to a reach, over the vertices a
// predicate admits; for many small walks over one large mesh, each resets only the vertices
// the previous one touched.
class BoundedWalk {
  public:
    BoundedWalk(const Mesh& mesh, const MeshTopology& topology, double reach)
        : mesh_(mesh),
          topology_(topology),
          reach_(reach),
          dist_(mesh.num_vertices(), std::numeric_limits<double>::infinity()) {}

    /// Walks from `sources` over the vertices where allowed(v). settle(v, d) is called once
    /// per vertex in order of distance (ties by vertex), and stops the walk when it returns
    /// false; reached(u, v) each time u's distance shrinks through its neighbour v.
    template <class Allowed, class Settle, class Reached>
    void run(const std::vector<int>& sources, Allowed&& allowed, Settle&& settle,
             Reached&& reached) {
        for (int v : touched_) dist_[v] = std::numeric_limits<double>::infinity();
        touched_.clear();
        queue_ = {};
        for (int v : sources)
            if (dist_[v] != 0) {
                if (dist_[v] == std::numeric_limits<double>::infinity()) touched_.push_back(v);
                dist_[v] = 0;
                queue_.emplace(0.0, v);
            }
        while (!queue_.empty()) {
            const auto [d, v] = queue_.top();
            queue_.pop();
            if (d > dist_[v]) continue;
            if (!settle(v, d)) return;
            for (int u : topology_.neighbours(v)) {
                const double du = d + (mesh_.positions[u] - mesh_.positions[v]).norm();
                if (du > reach_ || !(du < dist_[u]) || !allowed(u)) continue;
                if (dist_[u] == std::numeric_limits<double>::infinity()) touched_.push_back(u);
                dist_[u] = du;
                reached(u, v);
                queue_.emplace(du, u);
            }
        }
    }

    /// Distance of `v` in the last walk (infinity where it did not reach).
    double distance(int v) const { return dist_[v]; }
    /// The vertices the last walk reached.
    const std::vector<int>& touched() const { return touched_; }

  private:
    using Item = std::pair<double, int>;
    const Mesh& mesh_;
    const MeshTopology& topology_;
    double reach_;
    std::vector<double> dist_;
    std::vector<int> touched_;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue_;
};

constexpr auto kAnywhere = [](int) { return true; };            // BoundedWalk: no fence
constexpr auto kEverywhere = [](int, double) { return true; };  // BoundedWalk: no stop
constexpr auto kUnlabelled = [](int, int) {};                   // BoundedWalk: no labels

// For each vertex within `reach` of a texel of `set` along mesh edges, the nearest such
// texel (-1 elsewhere); only the texels where `use` is nonzero (empty: all). Multi-source
// Dijkstra; the queue orders ties by vertex, and a vertex of two texels starts with the lower
// index, so the labels depend on nothing else.
std::vector<int> nearest_texel(const Mesh& mesh, const MeshTopology& topology, const TexelSet& set,
                               double reach, const std::vector<char>& use = {}) {
    std::vector<int> label(mesh.num_vertices(), -1);
    std::vector<int> sources;
    for (std::size_t t = 0; t < set.texels.size(); ++t)
        if (use.empty() || use[t])
            for (int f : set.texels[t].faces)
                for (int v : mesh.faces[f])
                    if (label[v] < 0) {
                        label[v] = static_cast<int>(t);
                        sources.push_back(v);
                    }
    BoundedWalk(mesh, topology, reach).run(sources, kAnywhere, kEverywhere, [&](int u, int v) {
        label[u] = label[v];
    });
    return label;
}

// Rim flags of the texels of `set` (some vertex of the texel is nearest to a deeper texel of
// the other orientation), and of the texels of the other orientation, which of them make a
// rim; only the vertices where `evaluate` is nonzero (empty: all) count. Set, never cleared.
void rim_flags(const Mesh& mesh, const TexelSet& set, const std::vector<double>& depth,
               const std::vector<int>& other_label, const std::vector<double>& other_depth,
               const std::vector<char>& evaluate, std::vector<char>& rim,
               std::vector<char>& makes_rim) {
    for (std::size_t t = 0; t < set.texels.size(); ++t)
        for (int f : set.texels[t].faces)
            for (int v : mesh.faces[f]) {
                const int o = other_label[v];
                if (o >= 0 && other_depth[o] > depth[t] && (evaluate.empty() || evaluate[v]))
                    rim[t] = makes_rim[o] = 1;
            }
}

// The vertices within the margin of the texels that make a rim and are not rims themselves,
// or nothing when there is none.
std::vector<char> detail_vertices(const Mesh& mesh, const MeshTopology& topology,
                                  const TexelSet& set, const std::vector<char>& rim,
                                  const std::vector<char>& makes_rim, const RimParams& params,
                                  int& count) {
    count = 0;
    std::vector<char> use(rim.size());
    for (std::size_t t = 0; t < rim.size(); ++t) {
        use[t] = makes_rim[t] && !rim[t] ? 1 : 0;
        count += use[t];
    }
    if (count == 0) return {};
    return rim_detail_vertices(mesh, topology, set, use, params);
}

}  // namespace

bool rims_possible(const Mesh& mesh, const MeshTopology& topology,
                   const std::vector<Eigen::Vector3d>& vertex_normal,
                   const SmoothedSurface& smoothed, const TexelSet& set, const DepthMap& depth,
                   const RimParams& params) {
    const std::size_t nv = mesh.positions.size();
    if (vertex_normal.size() != nv || smoothed.positions.size() != nv ||
        depth.vertex_depth.size() != nv || topology.vertex_neighbour_offsets.size() != nv + 1 ||
        topology.face_neighbour_offsets.size() != mesh.faces.size() + 1)
        throw InvalidInput(
            "rims: topology, normals, smoothed positions and depths must have one row per vertex "
            "(" +
            std::to_string(nv) + ")");
    if (!(params.radius > 0) || !std::isfinite(params.radius) || !(params.reach_rel >= 0))
        throw InvalidInput(
            "rims: the radius must be positive and finite and the reach non-negative (got r = " +
            std::to_string(params.radius) + ", reach " + std::to_string(params.reach_rel) + ")");
    if (set.texels.empty()) return false;
    const std::vector<double> texel_depth = texel_depths(mesh, set, depth);
    const double shallowest = *std::min_element(texel_depth.begin(), texel_depth.end());
    // The other side: the mirror of make_depth_map's rule for `depth.orientation`.
    const double other = depth.orientation == DetailOrientation::Positive ? -1.0 : 1.0;
    const auto offset = [&](int v) -> Eigen::Vector3d {
        return mesh.positions[v] - smoothed.positions[v];
    };
    const auto moved = [&](int v) { return other * offset(v).dot(vertex_normal[v]) > 0; };
    // A vertex of the other side's oriented surface: its smoothed position where it moved.
    const auto oriented = [&](int v) -> const Eigen::Vector3d& {
        return moved(v) ? smoothed.positions[v] : mesh.positions[v];
    };
    // The tree's distance and these norms round differently (and so may the sums of edge
    // lengths below and in nearest_texel): a margin far above rounding and far below any
    // depth or length that matters.
    constexpr double kSlack = 1 + 1e-9;
    const auto reaches = [&](double bound, double depth_of_texel) {
        return bound * kSlack >= depth_of_texel;
    };

    // The deep vertices of the other side: those whose bound reaches the shallowest texel.
    std::vector<std::pair<int, double>> deep;  // vertex, bound
    for (int v = 0; v < static_cast<int>(nv); ++v) {
        if (!moved(v) || !reaches(offset(v).norm(), shallowest)) continue;
        // The distance to the own smoothed position overstates the depth wherever the disc
        // mean drifts sideways (beside a detail, by up to r/2: the raised shapes of sphere-1
        // level 9 and finer came out above their own shallowest texel that way). Any other
        // vertex of the oriented surface bounds the depth too: walk over the mesh to nearer
        // ones while they get nearer. Few vertices get here, each walks about drift / edge
        // steps.
        const Eigen::Vector3d& q = mesh.positions[v];
        double bound = (q - smoothed.positions[v]).norm();
        for (int at = v, next = v; reaches(bound, shallowest); at = next) {
            for (int u : topology.neighbours(at)) {
                const double d = (q - oriented(u)).norm();
                if (d < bound) {
                    bound = d;
                    next = u;
                }
            }
            if (next == at) break;
        }
        if (reaches(bound, shallowest)) deep.emplace_back(v, bound);
    }
    if (deep.empty()) return false;

    // Where some are, a texel of the other side deeper than one of ours still makes a rim only
    // within the reach of ours (make_rims). The texels of the other side do not exist yet, but
    // each lies in one part of the faces with a moved vertex joined across edges (a texel's
    // faces have depths at or above a positive threshold, and make_texels merges only regions
    // that share or touch faces), and its depth is at most the largest bound of the deep
    // vertices of that part. So walk the reach from each part that holds a deep vertex (finer
    // sphere-1 meshes: the rims of the tallest shapes reach the shallowest shape's depth, but
    // lie far from it). The walks cost at most #V settled vertices, else the answer is "maybe".
    const int nf = mesh.num_faces();
    const auto face_moved = [&](int f) {
        const auto& fv = mesh.faces[f];
        return moved(fv[0]) || moved(fv[1]) || moved(fv[2]);
    };
    std::vector<int> face_part(nf, -1);
    std::vector<int> part_faces, part_offsets{0};  // compressed rows, in labelling order
    std::vector<double> part_bound;
    std::vector<std::pair<int, int>> part_of_deep;  // part, deep vertex
    for (const auto& [v, bound] : deep)
        for (int f : topology.faces_of(v)) {
            if (face_part[f] < 0) {
                const int id = static_cast<int>(part_bound.size());
                part_bound.push_back(0.0);
                face_part[f] = id;
                std::size_t head = part_faces.size();
                part_faces.push_back(f);
                for (; head < part_faces.size(); ++head)
                    for (int g : topology.face_neighbours_of(part_faces[head]))
                        if (face_part[g] < 0 && face_moved(g)) {
                            face_part[g] = id;
                            part_faces.push_back(g);
                        }
                part_offsets.push_back(static_cast<int>(part_faces.size()));
            }
            part_bound[face_part[f]] = std::max(part_bound[face_part[f]], bound);
            part_of_deep.emplace_back(face_part[f], v);
        }
    std::vector<int>().swap(face_part);
    // The deep vertices of each part, in compressed rows.
    std::sort(part_of_deep.begin(), part_of_deep.end());
    part_of_deep.erase(std::unique(part_of_deep.begin(), part_of_deep.end()), part_of_deep.end());
    std::vector<int> part_deep, part_deep_offsets(part_bound.size() + 1, 0);
    for (const auto& [k, v] : part_of_deep) {
        part_deep.push_back(v);
        ++part_deep_offsets[k + 1];
    }
    std::partial_sum(part_deep_offsets.begin(), part_deep_offsets.end(), part_deep_offsets.begin());
    // The depth of the shallowest and of the deepest of our texels at each of their vertices.
    std::vector<double> ours(nv, std::numeric_limits<double>::infinity());
    std::vector<double> deepest_ours(nv, -std::numeric_limits<double>::infinity());
    for (std::size_t t = 0; t < set.texels.size(); ++t)
        for (int f : set.texels[t].faces)
            for (int v : mesh.faces[f]) {
                ours[v] = std::min(ours[v], texel_depth[t]);
                deepest_ours[v] = std::max(deepest_ours[v], texel_depth[t]);
            }
    const double reach = params.reach_rel * params.radius;
    BoundedWalk walk(mesh, topology, reach * kSlack);
    std::size_t num_settled = 0;
    std::vector<int> sources, ball, deep_sources, shallow_sources;
    std::vector<char> in_ball(nv, 0);
    std::vector<double> to_deep;
    for (std::size_t k = 0; k < part_bound.size(); ++k) {
        const double bound = part_bound[k];
        sources.clear();
        for (int i = part_offsets[k]; i < part_offsets[k + 1]; ++i)
            for (int v : mesh.faces[part_faces[i]]) sources.push_back(v);
        // The ball: everything within the reach of the part. A texel of ours shallower than
        // the part's bound in it may be a rim of the part's texel.
        bool shallow_near = false;
        walk.run(
            sources, kAnywhere,
            [&](int v, double) {
                shallow_near = shallow_near || reaches(bound, ours[v]);
                return ++num_settled <= nv;
            },
            kUnlabelled);
        if (num_settled > nv) return true;  // the walks would cost more than the depth map
        if (!shallow_near) continue;
        // Still nothing is left out when every texel of the other side in the part is a rim
        // itself (a tall detail's own rim, deeper than a small detail within its reach:
        // sphere-1 level 10). Such a texel's deepest vertex is a deep vertex of the part, and
        // make_rims calls the texel a rim when that vertex's nearest texel of ours (within the
        // reach) is deeper than the texel. So it is enough that at every deep vertex of the part
        // the texels of ours deeper than the bound are surely nearer than every other one. Every
        // path of length <= reach from the part stays in the ball, so the distances of walks
        // kept to the ball are exact wherever they matter.
        ball = walk.touched();
        for (int v : ball) in_ball[v] = 1;
        deep_sources.clear();
        shallow_sources.clear();
        for (int v : ball) {
            if (reaches(bound, ours[v])) shallow_sources.push_back(v);
            if (!reaches(bound, deepest_ours[v])) deep_sources.push_back(v);
        }
        const auto inside = [&](int v) { return in_ball[v] != 0; };
        walk.run(deep_sources, inside, kEverywhere, kUnlabelled);
        to_deep.clear();
        for (int i = part_deep_offsets[k]; i < part_deep_offsets[k + 1]; ++i)
            to_deep.push_back(walk.distance(part_deep[i]));
        walk.run(shallow_sources, inside, kEverywhere, kUnlabelled);
        for (int i = part_deep_offsets[k]; i < part_deep_offsets[k + 1]; ++i) {
            const double d = to_deep[i - part_deep_offsets[k]];
            if (!(d * kSlack <= reach && d * kSlack < walk.distance(part_deep[i]))) return true;
        }
        for (int v : ball) in_ball[v] = 0;
    }
    return false;
}

RimFlags no_rim_flags(std::size_t positive, std::size_t negative) {
    RimFlags out;
    out.positive_rim.assign(positive, 0);
    out.negative_rim.assign(negative, 0);
    out.positive_makes_rim.assign(positive, 0);
    out.negative_makes_rim.assign(negative, 0);
    return out;
}

RimFlags find_rims(const Mesh& mesh, const MeshTopology& topology, const TexelSet& positive,
                   const std::vector<double>& positive_depths, const TexelSet& negative,
                   const std::vector<double>& negative_depths, const RimParams& params,
                   const std::vector<char>& evaluate) {
    if (positive_depths.size() != positive.texels.size() ||
        negative_depths.size() != negative.texels.size())
        throw InvalidInput("rims: one depth per texel is needed");
    if (!evaluate.empty() && static_cast<int>(evaluate.size()) != mesh.num_vertices())
        throw InvalidInput("rims: the vertex flags do not match the mesh");
    RimFlags out = no_rim_flags(positive.texels.size(), negative.texels.size());
    if (positive.texels.empty() || negative.texels.empty()) return out;  // no rim of anything
    const double reach = params.reach_rel * params.radius;
    // The two orientations' walks are independent (each sequential, so deterministic): one
    // thread each (sphere-1 level 9 at 4%: the walks cover most of the mesh).
    std::vector<int> near_negative, near_positive;
    detail::parallel_invoke(
        [&] { near_negative = nearest_texel(mesh, topology, negative, reach); },
        [&] { near_positive = nearest_texel(mesh, topology, positive, reach); });
    rim_flags(mesh, positive, positive_depths, near_negative, negative_depths, evaluate,
              out.positive_rim, out.negative_makes_rim);
    rim_flags(mesh, negative, negative_depths, near_positive, positive_depths, evaluate,
              out.negative_rim, out.positive_makes_rim);
    return out;
}

std::vector<char> rim_detail_vertices(const Mesh& mesh, const MeshTopology& topology,
                                      const TexelSet& set, const std::vector<char>& use,
                                      const RimParams& params) {
    if (use.size() != set.texels.size()) throw InvalidInput("rims: one flag per texel is needed");
    const std::vector<int> label =
        nearest_texel(mesh, topology, set, params.margin_rel * params.radius, use);
    std::vector<char> out(mesh.num_vertices(), 0);
    for (int v = 0; v < mesh.num_vertices(); ++v) out[v] = label[v] >= 0 ? 1 : 0;
    return out;
}

Rims make_rims(const Mesh& mesh, const MeshTopology& topology, const TexelSet& positive,
               const DepthMap& positive_depth, const TexelSet& negative,
               const DepthMap& negative_depth, const RimParams& params) {
    if (!(params.radius > 0) || !std::isfinite(params.radius) || !(params.reach_rel >= 0))
        throw InvalidInput(
            "rims: the radius must be positive and finite and the reach non-negative (got r = " +
            std::to_string(params.radius) + ", reach " + std::to_string(params.reach_rel) + ")");
    const int nv = mesh.num_vertices();
    for (const DepthMap* d : {&positive_depth, &negative_depth})
        if (static_cast<int>(d->vertex_depth.size()) != nv)
            throw InvalidInput("rims: a depth map has " + std::to_string(d->vertex_depth.size()) +
                               " vertex depths for " + std::to_string(nv) + " vertices");
    if (positive_depth.orientation != DetailOrientation::Positive ||
        negative_depth.orientation != DetailOrientation::Negative)
        throw InvalidInput("rims: give the positive depth map first and the negative one second");
    Rims out;
    out.positive_rim.assign(positive.texels.size(), 0);
    out.negative_rim.assign(negative.texels.size(), 0);
    if (positive.texels.empty() || negative.texels.empty()) return out;  // no rim of anything
    const RimFlags flags =
        find_rims(mesh, topology, positive, texel_depths(mesh, positive, positive_depth), negative,
                  texel_depths(mesh, negative, negative_depth), params, {});
    out.positive_rim = flags.positive_rim;
    out.negative_rim = flags.negative_rim;
    const std::vector<char>& positive_makes_rim = flags.positive_makes_rim;
    const std::vector<char>& negative_makes_rim = flags.negative_makes_rim;
    detail::parallel_invoke(
        [&] {
            out.exclude_for_positive =
                detail_vertices(mesh, topology, negative, out.negative_rim, negative_makes_rim,
                                params, out.num_excluded_for_positive);
        },
        [&] {
            out.exclude_for_negative =
                detail_vertices(mesh, topology, positive, out.positive_rim, positive_makes_rim,
                                params, out.num_excluded_for_negative);
        });
    return out;
}

}  // namespace geotex
