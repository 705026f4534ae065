#include "geometry/curvature.hpp"

#include <cmath>
#include <limits>

#include "geometry/detail/parallel.hpp"
#include "geometry/errors.hpp"

namespace geotex {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double cotangent(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const double s = u.cross(v).norm();
    return u.dot(v) / s;  // caller skips zero-area faces, so s > 0
}

}  // namespace

CurvatureField make_curvature(const Mesh& mesh, const MeshTopology& topology,
                              const std::vector<Eigen::Vector3d>& vertex_normal,
                              const CurvatureParams& params) {
    const int nv = mesh.num_vertices();
    if (static_cast<int>(vertex_normal.size()) != nv)
        throw InvalidInput("curvature: vertex_normal has " + std::to_string(vertex_normal.size()) +
                           " rows for " + std::to_string(nv) + " vertices");
    CurvatureField c;
    c.gaussian.assign(nv, kNaN);
    c.mean.assign(nv, kNaN);
    c.shape_index.assign(nv, kNaN);
    c.curvedness.assign(nv, kNaN);
    const auto& p = mesh.positions;

    detail::parallel_for(nv, [&](int i) {
        if (topology.vertex_on_boundary[i] || topology.faces_of(i).size() == 0) return;
        double angle_sum = 0, area = 0;
        Eigen::Vector3d laplacian = Eigen::Vector3d::Zero();
        for (int f : topology.faces_of(i)) {
            const auto& fv = mesh.faces[f];
            const int corner = fv[0] == i ? 0 : (fv[1] == i ? 1 : 2);
            const int j = fv[(corner + 1) % 3], k = fv[(corner + 2) % 3];
            const Eigen::Vector3d eij = p[j] - p[i], eik = p[k] - p[i], ejk = p[k] - p[j];
            const double twice_area = eij.cross(eik).norm();
            if (!(twice_area > 0)) continue;  // a zero-area face carries no curvature
            const double cos_i = eij.dot(eik) / (eij.norm() * eik.norm());
            const double angle_i = std::acos(std::max(-1.0, std::min(1.0, cos_i)));
            angle_sum += angle_i;
            const double cot_j = cotangent(-eij, ejk);   // angle at j, opposite edge ik
            const double cot_k = cotangent(-eik, -ejk);  // angle at k, opposite edge ij
            laplacian += cot_k * (p[i] - p[j]) + cot_j * (p[i] - p[k]);
            // Mixed area (Meyer et al. §3.3): Voronoi part for non-obtuse triangles, else a
            // fixed share of the triangle so the areas still tile the surface.
            const double face_area = 0.5 * twice_area;
            const bool obtuse_i = eij.dot(eik) < 0;
            const bool obtuse_other = (-eij).dot(ejk) < 0 || (-eik).dot(-ejk) < 0;
            if (obtuse_i) area += face_area / 2;
            else if (obtuse_other) area += face_area / 4;
            else area += (eij.squaredNorm() * cot_k + eik.squaredNorm() * cot_j) / 8;
        }
        if (!(area > 0)) return;
        // A sum of a few acos values is exact to about 1e-15 rad; a smaller defect is a flat
        // vertex, and must give K = 0 exactly or sqrt(H^2 - K) would turn the rounding into
        // a curvature of sqrt(1e-15 / area).
        double defect = 2 * kPi - angle_sum;
        if (std::abs(defect) < 1e-12) defect = 0;
        const double k_gauss = defect / area;
        const double h_mean = 0.5 * laplacian.dot(vertex_normal[i]) / (2 * area);
        const double disc = std::sqrt(std::max(0.0, h_mean * h_mean - k_gauss));
        const double k1 = h_mean + disc, k2 = h_mean - disc;
        c.gaussian[i] = k_gauss;
        c.mean[i] = h_mean;
        c.curvedness[i] = std::sqrt((k1 * k1 + k2 * k2) / 2);
        if (c.curvedness[i] * std::sqrt(area) >= params.flat_tolerance)
            c.shape_index[i] = 2 / kPi * std::atan2(k1 + k2, k1 - k2);
    });
    return c;
}

}  // namespace geotex
