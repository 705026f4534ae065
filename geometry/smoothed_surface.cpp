#include "geometry/smoothed_surface.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/neighbourhood.hpp"

namespace geotex {

namespace {

// The disc means of `values`, keeping only their offset along the normal of v:
// v + ((mean - v) . n) n. The tangential part of the offset only
// slides the point along the surface, but where the disc is one-sided (a border, a hole)
// it pulls the smoothed surface back from the border by about 0.4 r, and the closest-point
// depth then reads that gap as relief: false texels along every border. Irregular
// sampling and noise drift the mean tangentially too (bench/RESULTS.md, "Design
// measurements": the projection lowers the error on noisy sphere-1, and changes nothing on
// the clean one).
std::vector<Eigen::Vector3d> normal_means(const DiscAverager& averager,
                                          const std::vector<Eigen::Vector3d>& values,
                                          const std::vector<double>& weight,
                                          const std::vector<Eigen::Vector3d>& normal) {
    std::vector<Eigen::Vector3d> out = averager.means(values, weight);
    detail::parallel_for(static_cast<int>(out.size()), [&](int v) {
        out[v] = values[v] + (out[v] - values[v]).dot(normal[v]) * normal[v];
    });
    return out;
}

// The disc weights, checked first so that the averager is built from valid inputs.
std::vector<double> smoothing_weights(const Mesh& mesh, const MeshMetrics& metrics,
                                      const SmoothingParams& params) {
    const std::vector<double>& vertex_area = metrics.vertex_area;
    if (!(params.radius > 0) || !std::isfinite(params.radius))
        throw InvalidInput("smoothing: the radius must be positive and finite (got " +
                           std::to_string(params.radius) + ")");
    const int nv = mesh.num_vertices();
    if (static_cast<int>(vertex_area.size()) != nv ||
        static_cast<int>(metrics.vertex_normal.size()) != nv)
        throw InvalidInput("smoothing: the metrics have " + std::to_string(vertex_area.size()) +
                           " areas and " + std::to_string(metrics.vertex_normal.size()) +
                           " normals for " + std::to_string(nv) + " vertices");
    std::vector<double> weight = params.area_weighted ? vertex_area : std::vector<double>(nv, 1.0);
    if (params.area_weighted)  // an isolated vertex weighs nothing but must not divide by 0
        for (double& w : weight) w = std::max(w, 0.0);
    return weight;
}

DiscMeanParams disc_params(const SmoothingParams& params) {
    DiscMeanParams dp;
    dp.radius = params.radius;
    dp.mode = params.disc;
    dp.sampling = params.sampling;
    return dp;
}

}  // namespace

SurfaceSmoother::SurfaceSmoother(const Mesh& mesh, const MeshTopology& topology,
                                 const MeshMetrics& metrics, const SmoothingParams& params)
    : mesh_(&mesh),
      topology_(&topology),
      normal_(&metrics.vertex_normal),
      params_(params),
      weight_(smoothing_weights(mesh, metrics, params)),
      averager_(mesh, topology, weight_, metrics.vertex_normal, disc_params(params)) {}

SmoothedSurface SurfaceSmoother::smooth(const std::vector<char>& excluded) const {
    const int nv = mesh_->num_vertices();
    if (!excluded.empty() && static_cast<int>(excluded.size()) != nv)
        throw InvalidInput("smoothing: " + std::to_string(excluded.size()) +
                           " exclusion flags for " + std::to_string(nv) + " vertices");
    // No vertex excluded is the plain smoothing, bit for bit.
    const bool masking =
        std::any_of(excluded.begin(), excluded.end(), [](char c) { return c != 0; });
    std::vector<double> masked;
    std::vector<Eigen::Vector3d> smoothed_normal;
    if (masking) {
        masked = weight_;
        for (int v = 0; v < nv; ++v)
            if (excluded[v]) masked[v] = 0;
        // With vertices left out, a disc beside them is one-sided and its mean drifts sideways
        // by up to r/2; projected on a vertex normal tilted by the wall of a detail next to it,
        // that drift reads as a depth of a quarter of the detail's height (measured at the
        // corners of engraved squares on sphere-1). Project on the normal of the smoothed
        // surface instead: the unit mean over the disc of the normals that no excluded vertex
        // tilts (those of vertices with no excluded neighbour); the vertex normal where the disc
        // has none.
        std::vector<double> untilted = masked;
        for (int v = 0; v < nv; ++v)
            if (excluded[v])
                for (int u : topology_->neighbours(v)) untilted[u] = 0;
        smoothed_normal = averager_.means(*normal_, untilted);
        detail::parallel_for(nv, [&](int v) {
            const double len = smoothed_normal[v].norm();
            smoothed_normal[v] =
                len > 0 ? Eigen::Vector3d(smoothed_normal[v] / len) : (*normal_)[v];
        });
    }
    const std::vector<double>& weight = masking ? masked : weight_;
    const std::vector<Eigen::Vector3d>& normal = masking ? smoothed_normal : *normal_;
    SmoothedSurface s;
    s.radius = params_.radius;
    s.num_interpolated_vertices = averager_.num_interpolated_vertices();
    s.num_samples = averager_.num_samples();
    s.positions = normal_means(averager_, mesh_->positions, weight, normal);
    if (params_.method == SmoothingMethod::Twicing) {
        const std::vector<Eigen::Vector3d> twice =
            normal_means(averager_, s.positions, weight, normal);
        for (int v = 0; v < nv; ++v) s.positions[v] = 2 * s.positions[v] - twice[v];
    }
    // An excluded vertex stays where it is: it belongs to a detail of the other orientation,
    // which has no depth in this one, and its mean, from beyond the detail, is the least
    // reliable (with vertex normals this read the walls of engravings as positive rims).
    if (masking)
        for (int v = 0; v < nv; ++v)
            if (excluded[v]) s.positions[v] = mesh_->positions[v];
    return s;
}

SmoothedSurface make_smoothed_surface(const Mesh& mesh, const MeshTopology& topology,
                                      const MeshMetrics& metrics, const SmoothingParams& params) {
    return SurfaceSmoother(mesh, topology, metrics, params).smooth();
}

}  // namespace geotex
