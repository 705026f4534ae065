#pragma once
// Closed contours of texels (docs/features.md, "Contour"): statistics over a contour are
// taken along its arc length, so that they are means over the curve and do not depend on
// how densely its vertices are spaced.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

namespace geotex::detail {

/// Length of the closed polyline c_0 ... c_{m-1} c_0.
inline double closed_length(const std::vector<Eigen::Vector3d>& c) {
    double length = 0;
    for (std::size_t i = 0; i < c.size(); ++i) length += (c[(i + 1) % c.size()] - c[i]).norm();
    return length;
}

/// Arc-length weight of each vertex of a closed polyline: half the length of its two edges
/// (the weights sum to the length).
inline std::vector<double> arc_weights(const std::vector<Eigen::Vector3d>& c) {
    const std::size_t m = c.size();
    std::vector<double> w(m, 0.0);
    for (std::size_t i = 0; i < m; ++i) {
        const double e = (c[(i + 1) % m] - c[i]).norm();
        w[i] += 0.5 * e;
        w[(i + 1) % m] += 0.5 * e;
    }
    return w;
}

/// Weighted mean and population standard deviation of x; (0, 0) when the weights sum to 0.
struct MeanStd {
    double mean = 0, std = 0;
};
inline MeanStd weighted_mean_std(const std::vector<double>& x, const std::vector<double>& w) {
    double sw = 0, sx = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        sw += w[i];
        sx += w[i] * x[i];
    }
    MeanStd r;
    if (!(sw > 0)) return r;
    r.mean = sx / sw;
    double sq = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sq += w[i] * (x[i] - r.mean) * (x[i] - r.mean);
    r.std = std::sqrt(sq / sw);
    return r;
}

}  // namespace geotex::detail
