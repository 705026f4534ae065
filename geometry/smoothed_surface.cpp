// make_smoothed_surface: the disc averages of paper eq. 1 and their twicing.

#include <cmath>
#include <string>

#include "geometry/depth_map.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/errors.hpp"
#include "geometry/neighbourhood.hpp"

namespace geotex {

namespace {

// The disc means of `values`, keeping only their offset along the normal of v:
// v + ((mean - v) . n) n. The tangential part of the offset only
// slides the point along the surface, but where the disc is one-sided (a border, a hole)
// it pulls the smoothed surface back from the border by about 0.4 r, and the closest-point
// depth then reads that gap as relief: false texels along every border. Irregular
// sampling and noise drift the mean tangentially too (measured on sphere-1 with noise
// I = 0.3: Hausdorff distance 2.5 -> 2.0 delta_t; on the clean sphere-1 nothing changes).
std::vector<Eigen::Vector3d> normal_means(const DiscAverager& averager, const std::vector<Eigen::Vector3d>& values,
                                          const std::vector<Eigen::Vector3d>& normal) {
    std::vector<Eigen::Vector3d> out = averager.means(values);
    detail::parallel_for(static_cast<int>(out.size()), [&](int v) {
        out[v] = values[v] + (out[v] - values[v]).dot(normal[v]) * normal[v];
    });
    return out;
}

}  // namespace

SmoothedSurface make_smoothed_surface(const Mesh& mesh, const MeshTopology& topology,
                                      const MeshMetrics& metrics, const SmoothingParams& params) {
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

    SmoothedSurface s;
    s.radius = params.radius;
    DiscMeanParams dp;
    dp.radius = params.radius;
    dp.mode = params.disc;
    const DiscAverager averager(mesh, topology, weight, metrics.vertex_normal, dp);
    s.num_interpolated_vertices = averager.num_interpolated_vertices();
    s.num_samples = averager.num_samples();
    s.positions = normal_means(averager, mesh.positions, metrics.vertex_normal);
    if (params.method == SmoothingMethod::Twicing) {
        const std::vector<Eigen::Vector3d> twice = normal_means(averager, s.positions, metrics.vertex_normal);
        for (int v = 0; v < nv; ++v) s.positions[v] = 2 * s.positions[v] - twice[v];
    }
    return s;
}

}  // namespace geotex
