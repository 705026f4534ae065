// make_smoothed_surface: the disc averages of paper eq. 1 and their twicing.

#include <cmath>
#include <string>

#include "geometry/depth_map.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/errors.hpp"
#include "geometry/neighbourhood.hpp"

namespace geotex {

namespace {

// Weighted mean of `values` over N_r(v) for every vertex v.
std::vector<Eigen::Vector3d> disc_means(const Mesh& mesh, const MeshTopology& topology,
                                        const std::vector<double>& weight,
                                        const std::vector<Eigen::Vector3d>& values, double radius) {
    const int nv = mesh.num_vertices();
    std::vector<Eigen::Vector3d> out(nv);
    detail::parallel_for_with(
        nv, [&] { return DiscWalker(mesh, topology); },
        [&](int v, DiscWalker& walker) {
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            double total = 0;
            for (int u : walker.disc(v, radius)) {
                sum += weight[u] * values[u];
                total += weight[u];
            }
            out[v] = total > 0 ? Eigen::Vector3d(sum / total) : values[v];
        });
    return out;
}

}  // namespace

SmoothedSurface make_smoothed_surface(const Mesh& mesh, const MeshTopology& topology,
                                      const std::vector<double>& vertex_area,
                                      const SmoothingParams& params) {
    if (!(params.radius > 0) || !std::isfinite(params.radius))
        throw InvalidInput("smoothing: the radius must be positive and finite (got " +
                           std::to_string(params.radius) + ")");
    const int nv = mesh.num_vertices();
    if (static_cast<int>(vertex_area.size()) != nv)
        throw InvalidInput("smoothing: vertex_area has " + std::to_string(vertex_area.size()) +
                           " rows for " + std::to_string(nv) + " vertices");
    std::vector<double> weight = params.area_weighted ? vertex_area : std::vector<double>(nv, 1.0);
    if (params.area_weighted)  // an isolated vertex weighs nothing but must not divide by 0
        for (double& w : weight) w = std::max(w, 0.0);

    SmoothedSurface s;
    s.radius = params.radius;
    s.positions = disc_means(mesh, topology, weight, mesh.positions, params.radius);
    if (params.method == SmoothingMethod::Twicing) {
        const std::vector<Eigen::Vector3d> twice =
            disc_means(mesh, topology, weight, s.positions, params.radius);
        for (int v = 0; v < nv; ++v) s.positions[v] = 2 * s.positions[v] - twice[v];
    }
    return s;
}

}  // namespace geotex
