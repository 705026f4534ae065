// The leading eigenpairs of a symmetric matrix, for the spectral clustering
// (clustering.cpp, step 3): Householder tridiagonalisation, all eigenvalues of the
// tridiagonal, inverse iteration for the wanted vectors and their back-transformation, with
// residual and orthogonality checks and Eigen's full solver as the fallback.

#pragma once

#include <Eigen/Core>

namespace geotex::detail {

struct Spectrum {
    Eigen::VectorXd values;   ///< #vectors, decreasing
    Eigen::MatrixXd vectors;  ///< #points by #vectors
};

/// The `count` leading eigenpairs of the symmetric `l` (#points by #points; eigenvalues
/// decreasing), each vector's sign fixed so that its largest-magnitude entry (smallest index
/// on ties) is positive. Tries the partial solver and falls back to the full one. Throws
/// NumericalError when neither converges.
Spectrum leading_eigenpairs(const Eigen::MatrixXd& l, int count);

}  // namespace geotex::detail
