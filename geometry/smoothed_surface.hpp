#pragma once
/// The smoothed surface of paper §3.1, eq. 1: every vertex moved to the mean of its geodesic
/// disc N_r(v) (or its twicing), along its normal. depth_map.hpp measures the distance to it.

#include <optional>
#include <string_view>
#include <vector>

#include "geometry/disc_means.hpp"
#include "geometry/enum_names.hpp"
#include "geometry/mesh.hpp"
#include "geometry/topology.hpp"

namespace geotex {

/// How the disc average of eq. 1 is turned into the smoothed surface.
enum class SmoothingMethod {
    /// The paper's eq. 1: v_s = mean of N_r(v). A convex surface shrinks by about
    /// H r^2 / 2 (r^2 / 4R on a sphere of radius R), so curved regions get a depth even
    /// without any detail.
    Mean,
    /// Twicing (Tukey): v_s = 2 M(v) - M(M(v)) with M the disc mean. Removes the r^2 term
    /// of the shrinkage (a sphere keeps its radius to within r^4 / 16R^3) while the
    /// detail, narrower than the disc, is still smoothed away. The default.
    Twicing,
};

/// The names of the smoothing methods in options, reports and RDF literals.
inline constexpr std::array<std::pair<const char*, SmoothingMethod>, 2> kSmoothingMethodNames = {
    {{"twicing", SmoothingMethod::Twicing}, {"mean", SmoothingMethod::Mean}}};
inline const char* name_of(SmoothingMethod m) { return name_in(kSmoothingMethodNames, m); }
/// The method named `name` ("twicing", "mean"); nullopt for another name.
inline std::optional<SmoothingMethod> parse_smoothing_method(std::string_view name) {
    return value_in(kSmoothingMethodNames, name);
}

struct SmoothingParams {
    double radius = 0;  ///< r, mesh units; must be > 0
    SmoothingMethod method = SmoothingMethod::Twicing;
    bool area_weighted = true;       ///< weight disc vertices by their area (one third of the
                                     ///< incident faces) so that irregular sampling does not bias
                                     ///< the mean; false gives eq. 1's plain vertex mean
    DiscMode disc = DiscMode::Auto;  ///< exact disc walks, or exact at samples and
                                     ///< interpolated (see DiscMode; Auto: fast on large discs)
    /// The whole mesh's sampling when the mesh smoothed is a tile of it (DiscMeanParams);
    /// null: the mesh's own. Not owned.
    const DiscSampling* sampling = nullptr;
};

/// Smoothed, not yet oriented, vertex positions v_s.
struct SmoothedSurface {
    std::vector<Eigen::Vector3d> positions;  ///< #V
    double radius = 0;                       ///< r used, mesh units
    int num_interpolated_vertices = 0;       ///< vertices whose disc means were interpolated
    int num_samples = 0;                     ///< exact discs walked as samples of the fast mode
};

/// Disc averages of every vertex (paper eq. 1, or twicing), each moved along the vertex
/// normal only: v_s = v + ((M(v) - v) . n(v)) n(v), so that one-sided discs at borders and
/// holes do not pull the surface back from the border (smoothed_surface.cpp says why).
/// O(#V * |N_r|) exact, O(#V) in the fast mode (DiscMode), parallel over vertices. Uses
/// `metrics.vertex_area` (weights) and `metrics.vertex_normal`. Throws InvalidInput when the radius
/// is not positive and finite or the metrics do not have one row per vertex.
SmoothedSurface make_smoothed_surface(const Mesh& mesh, const MeshTopology& topology,
                                      const MeshMetrics& metrics, const SmoothingParams& params);

/// The smoothing of make_smoothed_surface set up once (the disc walks, the fast mode's
/// samples) and applied several times, with some vertices left out of the discs (the
/// second pass that removes rims, docs/rims.md). Holds pointers to its inputs: they must
/// outlive it. Throws as make_smoothed_surface.
class SurfaceSmoother {
  public:
    SurfaceSmoother(const Mesh& mesh, const MeshTopology& topology, const MeshMetrics& metrics,
                    const SmoothingParams& params);
    SurfaceSmoother(const SurfaceSmoother&) = delete;  // the averager points at weight_
    SurfaceSmoother& operator=(const SurfaceSmoother&) = delete;
    /// make_smoothed_surface's result, with the vertices where `excluded` is nonzero weighing
    /// nothing in every disc mean; those vertices keep their own position (depth 0 for either
    /// orientation), and the others move along the smoothed surface's normal rather than their
    /// own (smoothed_surface.cpp says why). `excluded` is #V, or empty; with none excluded, the
    /// same bits as make_smoothed_surface. Throws InvalidInput on another size.
    SmoothedSurface smooth(const std::vector<char>& excluded = {}) const;
    /// The disc means' setup: which vertices are samples and which are interpolated.
    const DiscAverager& averager() const { return averager_; }

  private:
    const Mesh* mesh_;
    const MeshTopology* topology_;
    const std::vector<Eigen::Vector3d>* normal_;
    SmoothingParams params_;
    std::vector<double> weight_;  // #V
    DiscAverager averager_;
};

}  // namespace geotex
