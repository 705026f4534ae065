#include "geometry/curvature.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

#include "common/detail/numbers.hpp"
#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/neighbourhood.hpp"

namespace geotex {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double cotangent(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const double s = u.cross(v).norm();
    return u.dot(v) / s;  // caller skips zero-area faces, so s > 0
}

// Principal curvatures, shape index and curvedness of vertex i from K and H.
void set_curvatures(CurvatureField& c, int i, double k_gauss, double h_mean, double area,
                    const CurvatureParams& params) {
    const double disc = std::sqrt(std::max(0.0, h_mean * h_mean - k_gauss));
    const double k1 = h_mean + disc, k2 = h_mean - disc;
    c.gaussian[i] = k_gauss;
    c.mean[i] = h_mean;
    c.curvedness[i] = std::sqrt((k1 * k1 + k2 * k2) / 2);
    if (c.curvedness[i] * std::sqrt(area) >= params.flat_tolerance)
        c.shape_index[i] = 2 / kPi * std::atan2(k1 + k2, k1 - k2);
}

// Gaussian and mean curvature (mean positive where convex) at (0, 0) of a height field
// z = f(x, y) over the tangent plane of `n`, from its first and second derivatives.
struct HeightDerivatives {
    double fx, fy, fxx, fxy, fyy;
};

std::pair<double, double> height_field_curvature(const HeightDerivatives& d) {
    const double g = 1 + d.fx * d.fx + d.fy * d.fy;
    const double k_gauss = (d.fxx * d.fyy - d.fxy * d.fxy) / (g * g);
    const double h_mean =
        -((1 + d.fy * d.fy) * d.fxx - 2 * d.fx * d.fy * d.fxy + (1 + d.fx * d.fx) * d.fyy) /
        (2 * g * std::sqrt(g));
    return {k_gauss, h_mean};
}

// The fit uses at most this many vertices, the nearest in breadth-first order, so that the
// cost per vertex stays bounded at high resolution. A cut disc is a smaller disc: the
// curvature is then measured at a smaller scale than asked, and the texture features move
// with the resolution. 512 holds the whole disc (0.6 r, the default curvature scale) up to
// sphere-1 level 8 at r = 4%, where the features equal those of uncut discs; level 9 at 4%
// (about 1,500 vertices) is still cut. bench/RESULTS.md ("Design measurements") has the
// measurements behind the bound.
constexpr int kMaxFitVertices = 512;

// Fits z = A X^2 + B XY + C Y^2 + D X + E Y + F (X, Y, Z: coordinates over rho in the frame of
// the disc's mean normal) to the disc of `center` by weighted least squares, the weights being
// vertex areas times (1 - d^2 / rho^2)^2 so that the fit fades out at the disc's rim. The
// constant term lets the surface pass beside the centre vertex, whose own noise would
// otherwise bend the whole fit. Returns false when the disc is too small or the fit is
// ill-conditioned (all vertices on a curve).
bool fit_quadric(const Mesh& mesh, const std::vector<Eigen::Vector3d>& vertex_normal,
                 const std::vector<double>& vertex_area, IndexRange disc, int center, double rho,
                 double& k_gauss, double& h_mean) {
    constexpr int kMinVertices = 10;
    if (disc.size() < kMinVertices) return false;
    const Eigen::Vector3d& c = mesh.positions[center];
    // A disc cut at kMaxFitVertices fades out at its farthest vertex instead.
    if (disc.size() >= kMaxFitVertices) {
        double far2 = 0;
        for (int u : disc) far2 = std::max(far2, (mesh.positions[u] - c).squaredNorm());
        rho = std::min(rho, std::sqrt(far2) * 1.05);
    }
    const double rho2 = rho * rho;
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int u : disc) n += vertex_area[u] * vertex_normal[u];
    if (!(n.norm() > 0)) return false;
    n.normalize();
    // A tangent frame: the axis least aligned with n, made orthogonal to it.
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    Eigen::Index smallest = 0;
    n.cwiseAbs().minCoeff(&smallest);
    axis[smallest] = 1;
    const Eigen::Vector3d t1 = (axis - axis.dot(n) * n).normalized();
    const Eigen::Vector3d t2 = n.cross(t1);
    Eigen::Matrix<double, 6, 6> normal_matrix = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    for (int u : disc) {
        const Eigen::Vector3d e = mesh.positions[u] - c;
        const double fade = std::max(0.0, 1 - e.squaredNorm() / rho2);
        const double w = vertex_area[u] * fade * fade;
        if (!(w > 0)) continue;
        const double x = e.dot(t1) / rho, y = e.dot(t2) / rho, z = e.dot(n) / rho;
        Eigen::Matrix<double, 6, 1> phi;
        phi << x * x, x * y, y * y, x, y, 1;
        // The lower triangle of w phi phi^T added as Eigen's rankUpdate adds it, (w phi_i)
        // phi_j column by column, so the fit keeps its bits; written out because rankUpdate
        // goes through Eigen's general rank-1 kernel, a call and a loop per column for each
        // disc vertex (sphere-1 level 7 at 16%: the curvature stage 0.13 s, 0.11 without).
        for (int i = 0; i < 6; ++i) {
            const double wi = w * phi[i];
            for (int j = i; j < 6; ++j) normal_matrix(j, i) += wi * phi[j];
        }
        rhs += w * z * phi;
    }
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(
        normal_matrix.selfadjointView<Eigen::Lower>());
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.rcond() > 1e-10))
        return false;
    const Eigen::Matrix<double, 6, 1> q = ldlt.solve(rhs);
    const auto [k, h] =
        height_field_curvature({q[3], q[4], 2 * q[0] / rho, q[1] / rho, 2 * q[2] / rho});
    if (!std::isfinite(k) || !std::isfinite(h)) return false;
    k_gauss = k;
    h_mean = h;
    return true;
}

}  // namespace

CurvatureField make_curvature(const Mesh& mesh, const MeshTopology& topology,
                              const std::vector<Eigen::Vector3d>& vertex_normal,
                              const CurvatureParams& params) {
    const int nv = mesh.num_vertices();
    expect_vertex_faces(mesh, topology, "curvature");
    if (static_cast<int>(vertex_normal.size()) != nv)
        throw InvalidInput("curvature: vertex_normal has " + std::to_string(vertex_normal.size()) +
                           " rows for " + std::to_string(nv) + " vertices");
    CurvatureField c;
    c.gaussian.assign(nv, kNaN);
    c.mean.assign(nv, kNaN);
    c.shape_index.assign(nv, kNaN);
    c.curvedness.assign(nv, kNaN);
    const auto& p = mesh.positions;
    if (!params.only.empty() && static_cast<int>(params.only.size()) != nv)
        throw InvalidInput("curvature: the vertex mask has " + std::to_string(params.only.size()) +
                           " entries for " + std::to_string(nv) + " vertices");
    if (!(params.radius >= 0) || !std::isfinite(params.radius))
        throw InvalidInput("curvature: the radius must be 0 or positive and finite (got " +
                           std::to_string(params.radius) + ")");
    // One third of each face's area to each corner: the weights of the quadric fit.
    std::vector<double> vertex_area(static_cast<std::size_t>(nv), 0.0);
    if (params.radius > 0)
        for (const auto& f : mesh.faces) {
            const double a = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]).norm() / 6;
            for (int v : f) vertex_area[v] += a;
        }

    detail::parallel_for_with(
        nv, [&] { return DiscWalker(mesh, topology); },
        [&](int i, DiscWalker& walker) {
            if (topology.vertex_on_boundary[i] || topology.faces_of(i).size() == 0) return;
            if (!params.only.empty() && !params.only[i]) return;
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
                if (obtuse_i)
                    area += face_area / 2;
                else if (obtuse_other)
                    area += face_area / 4;
                else
                    area += (eij.squaredNorm() * cot_k + eik.squaredNorm() * cot_j) / 8;
            }
            if (!(area > 0)) return;
            double k_gauss = 0, h_mean = 0;
            if (params.radius > 0 && fit_quadric(mesh, vertex_normal, vertex_area,
                                                 walker.disc(i, params.radius, kMaxFitVertices), i,
                                                 params.radius, k_gauss, h_mean)) {
                set_curvatures(c, i, k_gauss, h_mean, area, params);
                return;
            }
            // A sum of a few acos values is exact to about 1e-15 rad; a smaller defect is a flat
            // vertex, and must give K = 0 exactly or sqrt(H^2 - K) would turn the rounding into
            // a curvature of sqrt(1e-15 / area).
            double defect = 2 * kPi - angle_sum;
            if (std::abs(defect) < 1e-12) defect = 0;
            k_gauss = defect / area;
            h_mean = 0.5 * laplacian.dot(vertex_normal[i]) / (2 * area);
            set_curvatures(c, i, k_gauss, h_mean, area, params);
        });
    return c;
}

}  // namespace geotex
