#pragma once
/// Weighted means over the geodesic discs N_r(v) of every vertex (paper §3.1, eq. 1), exact
/// or interpolated from a sparse set of exact discs. docs/disc-means.md explains the fast
/// mode and its measured error.

#include <cstddef>
#include <vector>

#include "geometry/disc_clusters.hpp"
#include "geometry/enum_names.hpp"
#include "geometry/mesh.hpp"
#include "geometry/neighbourhood.hpp"
#include "geometry/topology.hpp"

namespace geotex {

/// How the disc means are evaluated.
enum class DiscMode {
    /// Every vertex walks its own disc: O(#V * |N_r|), the reference.
    Exact,
    /// Exact discs at samples about `sample_spacing_rel * r` apart, interpolated at the other
    /// vertices with a second-order correction: O(#V), whatever the radius.
    Fast,
    /// Fast on the connected components where the disc holds at least
    /// `auto_min_disc_vertices` vertices (estimated as pi r^2 #V_c / area_c, at most #V_c),
    /// exact elsewhere (small discs and small components, where sampling saves little).
    Auto,
};

/// The names of the disc modes in options, reports and RDF literals.
inline constexpr std::array<std::pair<const char*, DiscMode>, 3> kDiscModeNames = {
    {{"auto", DiscMode::Auto}, {"exact", DiscMode::Exact}, {"fast", DiscMode::Fast}}};
inline const char* name_of(DiscMode m) { return name_in(kDiscModeNames, m); }
/// The mode named `name` ("auto", "exact", "fast"); nullopt for another name.
inline std::optional<DiscMode> parse_disc_mode(std::string_view name) {
    return value_in(kDiscModeNames, name);
}

/// The fast mode's choices that depend on the whole mesh: which vertices are sampled (Auto
/// estimates the disc size per connected component) and the sampling grid's corner. A tile of
/// a mesh (tiles.hpp) takes its whole mesh's, so that its discs are sampled as the whole
/// mesh's are and its disc means are the same.
struct DiscSampling {
    std::vector<char> fast;                            ///< #V: sampled (fast), else exact
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< lowest corner of the grid
    bool grid = true;  ///< false: too many cells per axis, nothing is sampled
};

struct DiscMeanParams {
    double radius = 0;  ///< r, mesh units; must be > 0
    DiscMode mode = DiscMode::Auto;
    double sample_spacing_rel = 0.25;     ///< s: sample spacing (cell of the sampling grid) / r
    double support_rel = 2.0;             ///< h: interpolation radius / s, >= 1.8 (a vertex's own
                                          ///< cell sample is within sqrt(3) s), and
                                          ///< (h/s + sqrt(3)) s/r <= 1
    double auto_min_disc_vertices = 400;  ///< Auto: least estimated disc size for Fast
    bool exact_samples = false;           ///< walk the samples' discs vertex by vertex (cost
                                 ///< #samples x |N_r|, grows with the resolution) instead of
                                 ///< summing patches (cost independent of the resolution)
    /// Discs averaged exactly are walked once, at setup, cluster by cluster
    /// (disc_clusters.hpp), and recorded for every call to means() (twicing makes two), up
    /// to this many integers in all (about one per 3 disc vertices); the rest are walked
    /// again by each call. 0 records nothing. Results do not depend on it.
    std::size_t max_recorded_disc_vertices = std::size_t{1} << 27;
    /// The whole mesh's sampling when the mesh averaged is a tile of it (make_disc_sampling on
    /// the whole mesh, restricted to the tile's vertices); null: the mesh's own. Not owned.
    const DiscSampling* sampling = nullptr;
};

/// The sampling `params` give the whole of `mesh` (`params.sampling` is ignored): what a
/// DiscAverager over the mesh uses, for its tiles to use too. `components`, when given, are
/// vertex_components(mesh), made already by the caller (null: made here).
DiscSampling make_disc_sampling(const Mesh& mesh, const DiscMeanParams& params,
                                const VertexComponents* components = nullptr);
/// The same for a mesh whose `num_faces` faces are read a block at a time, with its
/// components (vertex_components of the same faces).
DiscSampling make_disc_sampling(PositionSpan positions, const FaceBlockReader& faces,
                                std::size_t num_faces, const DiscMeanParams& params,
                                const VertexComponents& components);

/// Evaluates disc means of any per-vertex field over the same discs. Setup (components,
/// sampling, candidate samples) is done once and reused by each call to means(), e.g. for
/// the two passes of twicing. Holds pointers to its inputs: they must outlive it.
class DiscAverager {
  public:
    /// `weight` is #V, >= 0 (vertex areas, or ones); `normal` is #V, unit (vertex normals,
    /// used by the fast mode's correction). Throws InvalidInput when the radius is not
    /// positive and finite, a size does not match #V, or a fast-mode parameter is out of
    /// range.
    DiscAverager(const Mesh& mesh, const MeshTopology& topology, const std::vector<double>& weight,
                 const std::vector<Eigen::Vector3d>& normal, const DiscMeanParams& params);

    /// M(v) = sum_{u in N_r(v)} w_u values_u / sum w_u for every vertex (#V; values_v where the
    /// disc weighs nothing); interpolated where the mode is fast. `values` is #V. Parallel,
    /// and the same for any thread count.
    std::vector<Eigen::Vector3d> means(const std::vector<Eigen::Vector3d>& values) const;
    /// The same means over the same discs with other weights (#V, >= 0), e.g. the setup's with
    /// some vertices set to 0 so that they do not pull the mean; values_v where the disc weighs
    /// nothing. The fast mode's normals keep the setup's weights. Throws InvalidInput when a
    /// size does not match #V.
    std::vector<Eigen::Vector3d> means(const std::vector<Eigen::Vector3d>& values,
                                       const std::vector<double>& weight) const;

    /// Vertices whose means are interpolated (0 in Exact mode).
    int num_interpolated_vertices() const { return num_interpolated_; }
    /// Vertices whose discs are walked exactly as samples of the fast mode.
    int num_samples() const { return static_cast<int>(sample_vertex_.size()); }
    /// Whether vertex v's mean is interpolated (a tile counts those it owns).
    bool interpolated(int v) const { return vertex_patch_[v] >= 0; }
    /// The vertices whose discs are walked exactly as samples.
    const std::vector<int>& sample_vertices() const { return sample_vertex_; }

  private:
    // The fast mode's setup; clears walked[v] for the vertices of components it samples.
    void setup_fast(const DiscMeanParams& params, std::vector<char>& walked);

    const Mesh* mesh_;
    const MeshTopology* topology_;
    const std::vector<double>* weight_;
    const std::vector<Eigen::Vector3d>* normal_;
    double radius_ = 0;
    bool exact_samples_ = false;
    double support_ = 0;                  // h, mesh units
    std::vector<int> vertex_patch_;       // #V: patch id, or -1 for an exactly averaged vertex
    std::vector<int> sample_vertex_;      // #patches: the sample vertex of each patch
    std::vector<int> candidate_offsets_;  // #patches + 1
    std::vector<int> candidates_;         // samples (patch ids) a vertex of the patch may use
    std::vector<Eigen::Vector3d> patch_normal_sum_;  // #patches, sum of weight x normal
    std::vector<int> disc_offsets_;                  // #patches + 1: the disc of each sample,
    std::vector<int> disc_patches_;                  // as patches
    std::vector<double> disc_fractions_;             // and the fraction of each inside the ball
    int num_interpolated_ = 0;
    WalkGraph walk_graph_;                // the components averaged exactly, in walking order
    DiscClusters clusters_;               // of walk_graph_'s vertices
    std::vector<ClusterDiscs> recorded_;  // per cluster; an empty core: not recorded
};

}  // namespace geotex
