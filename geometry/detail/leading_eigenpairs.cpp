// The leading eigenpairs of the clustering's normalised affinity matrix
// (leading_eigenpairs.hpp): linear algebra apart from the clustering that reads them.

// GCC 12 reports -Wmaybe-uninitialized false positives inside Eigen 3.4's tridiagonalisation
// when Eigen is not included as a system header (CMake's Eigen3::Eigen target is).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include "geometry/detail/leading_eigenpairs.hpp"

#include <Eigen/Eigenvalues>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"

namespace geotex::detail {
namespace {

std::size_t at(Eigen::Index i) { return static_cast<std::size_t>(i); }

/// LU factorisation with partial pivoting of the symmetric tridiagonal T - shift I
/// (diagonal `d`, off-diagonal `e`); U keeps two superdiagonals.
class ShiftedTridiagonalLu {
  public:
    ShiftedTridiagonalLu(const Eigen::VectorXd& d, const Eigen::VectorXd& e, double shift,
                         double pivot_floor)
        : n_(d.size()), u0_(n_), u1_(n_), u2_(n_), mult_(n_), swap_(at(n_)) {
        u1_.setZero();
        u2_.setZero();
        mult_.setZero();
        double c0 = d(0) - shift, c1 = n_ > 1 ? e(0) : 0.0, c2 = 0.0;
        for (Eigen::Index i = 0; i + 1 < n_; ++i) {
            const double n0 = e(i), n1 = d(i + 1) - shift, n2 = i + 2 < n_ ? e(i + 1) : 0.0;
            const bool swap = std::abs(n0) > std::abs(c0);
            swap_[at(i)] = swap;
            if (swap) {
                const double m = c0 / n0;
                u0_(i) = n0, u1_(i) = n1, u2_(i) = n2;
                c0 = c1 - m * n1, c1 = c2 - m * n2, c2 = 0.0;
                mult_(i) = m;
            } else {
                if (c0 == 0.0) c0 = pivot_floor;  // n0 is 0 too: T splits here
                const double m = n0 / c0;
                u0_(i) = c0, u1_(i) = c1, u2_(i) = c2;
                c0 = n1 - m * c1, c1 = n2 - m * c2, c2 = 0.0;
                mult_(i) = m;
            }
        }
        // An exactly singular pivot means the shift is an exact eigenvalue; a tiny one
        // still gives the direction we want.
        u0_(n_ - 1) = c0 == 0.0 ? pivot_floor : c0;
    }

    Eigen::VectorXd solve(Eigen::VectorXd b) const {
        for (Eigen::Index i = 0; i + 1 < n_; ++i) {
            if (swap_[at(i)]) std::swap(b(i), b(i + 1));
            b(i + 1) -= mult_(i) * b(i);
        }
        for (Eigen::Index i = n_ - 1; i >= 0; --i) {
            double v = b(i);
            if (i + 1 < n_) v -= u1_(i) * b(i + 1);
            if (i + 2 < n_) v -= u2_(i) * b(i + 2);
            b(i) = v / u0_(i);
        }
        return b;
    }

  private:
    Eigen::Index n_;
    Eigen::VectorXd u0_, u1_, u2_, mult_;
    std::vector<char> swap_;
};

/// The `count` leading eigenpairs of the symmetric `l` by a full dense solve.
Spectrum dense_leading_eigenpairs(const Eigen::MatrixXd& l, int count) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(l);
    if (solver.info() != Eigen::Success)
        throw NumericalError(std::string("clustering: eigen solver did not converge on the ") +
                             std::to_string(l.rows()) + " x " + std::to_string(l.rows()) +
                             " normalised affinity matrix");
    const Eigen::Index n = l.rows();
    Spectrum out;
    out.values.resize(count);
    out.vectors.resize(n, count);
    for (int c = 0; c < count; ++c) {  // Eigen sorts increasingly
        out.values(c) = solver.eigenvalues()(n - 1 - c);
        out.vectors.col(c) = solver.eigenvectors().col(n - 1 - c);
    }
    return out;
}

/// The `count` leading eigenpairs of the symmetric `l` without forming all eigenvectors:
/// Householder tridiagonalisation L = Q T Q^T, all eigenvalues of T, inverse iteration on T
/// for the `count` largest only (each iterate orthogonalised against the vectors found
/// before, which separates repeated eigenvalues), then x = Q v. The full solver spends
/// most of its time accumulating all n eigenvectors; this is about 4 times faster at
/// n = 2000. Returns false (and leaves `out` unspecified) when a residual or the
/// orthogonality check fails.
bool partial_leading_eigenpairs(const Eigen::MatrixXd& l, int count, Spectrum* out) {
    const Eigen::Index n = l.rows();
    const Eigen::Tridiagonalization<Eigen::MatrixXd> tri(l);
    const Eigen::VectorXd d = tri.diagonal();
    const Eigen::VectorXd e = tri.subDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> values_only;
    values_only.computeFromTridiagonal(d, e, Eigen::EigenvaluesOnly);
    if (values_only.info() != Eigen::Success) return false;

    double norm = 0.0;  // infinity norm of T, the scale of rounding errors
    for (Eigen::Index i = 0; i < n; ++i)
        norm = std::max(norm, std::abs(d(i)) + (i > 0 ? std::abs(e(i - 1)) : 0.0) +
                                  (i + 1 < n ? std::abs(e(i)) : 0.0));
    const double eps = std::numeric_limits<double>::epsilon();
    const double pivot_floor = std::max(norm, 1.0) * eps;

    Eigen::MatrixXd v(n, count);
    out->values.resize(count);
    for (int c = 0; c < count; ++c) {
        const double lambda = values_only.eigenvalues()(n - 1 - c);
        out->values(c) = lambda;
        const ShiftedTridiagonalLu lu(d, e, lambda, pivot_floor);
        // A fixed start vector with no symmetry, so that it is not orthogonal to the wanted
        // eigenvector by construction; the final checks catch the unlucky case.
        Eigen::VectorXd y(n);
        for (Eigen::Index i = 0; i < n; ++i)
            y(i) = 1.0 + 0.5 * std::sin(0.7 * static_cast<double>(i) + 1.3 * c);
        for (int iter = 0; iter < 4; ++iter) {
            y = lu.solve(y);
            for (int k = 0; k < c; ++k) y -= v.col(k).dot(y) * v.col(k);
            const double len = y.norm();
            if (!(len > 0.0) || !std::isfinite(len)) return false;
            y /= len;
        }
        v.col(c) = y;
    }
    out->vectors = tri.matrixQ() * v;

    const double tolerance = 1e-9 * std::max(norm, 1.0);
    const Eigen::MatrixXd residual = l * out->vectors - out->vectors * out->values.asDiagonal();
    for (int c = 0; c < count; ++c)
        if (!(residual.col(c).norm() <= tolerance)) return false;
    const Eigen::MatrixXd gram = out->vectors.transpose() * out->vectors;
    if (!((gram - Eigen::MatrixXd::Identity(count, count)).cwiseAbs().maxCoeff() <= 1e-9))
        return false;
    return true;
}

}  // namespace

Spectrum leading_eigenpairs(const Eigen::MatrixXd& l, int count) {
    Spectrum out;
    if (!partial_leading_eigenpairs(l, count, &out)) out = dense_leading_eigenpairs(l, count);
    for (int c = 0; c < count; ++c) {
        Eigen::Index arg = 0;
        out.vectors.col(c).cwiseAbs().maxCoeff(&arg);
        if (out.vectors(arg, c) < 0.0) out.vectors.col(c) *= -1.0;
    }
    return out;
}

}  // namespace geotex::detail
