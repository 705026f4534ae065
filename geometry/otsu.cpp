#include "geometry/otsu.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"

namespace geotex {

namespace {

// Below this many values a sort is not worth splitting over threads.
constexpr std::size_t kParallelSortSize = std::size_t{1} << 16;

}  // namespace

OtsuResult otsu_threshold(std::vector<double> values) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i]))
            throw InvalidInput("Otsu threshold: value " + std::to_string(i) + " is not finite");
        // -0.0 as 0.0: equal values then have equal bits, and every sort gives one sequence.
        if (values[i] == 0) values[i] = 0.0;
    }
    OtsuResult result;
    result.threshold = std::numeric_limits<double>::infinity();
    const std::size_t n = values.size();
    if (n < 2) return result;
    // A whole mesh's depths (tens of millions at level 11) are most of a texel job's sorting;
    // a seed's disc, sorted inside a parallel loop, stays on its thread.
    if (n >= kParallelSortSize)
        detail::parallel_sort(values);
    else
        std::sort(values.begin(), values.end());
    if (values.front() == values.back()) return result;

    // Shift by the mean so the running sums stay well conditioned.
    double mean = 0;
    for (double v : values) mean += v;
    mean /= static_cast<double>(n);
    double total_var = 0;
    for (double v : values) total_var += (v - mean) * (v - mean);
    total_var /= static_cast<double>(n);

    // With values centred on their mean, the between-class variance of the split
    // [0,k) | [k,n) is w0 w1 (m0 - m1)^2 = S0^2 / (k (n - k)), where S0 is the centred sum
    // of the lower class (the upper class sums to -S0).
    double best = -1, s0 = 0;
    std::size_t best_k = 0;
    for (std::size_t k = 1; k < n; ++k) {
        s0 += values[k - 1] - mean;
        if (values[k] == values[k - 1]) continue;  // only split between distinct values
        const double kk = static_cast<double>(k), nn = static_cast<double>(n);
        const double between = s0 * s0 / (kk * (nn - kk));
        if (between > best) {
            best = between;
            best_k = k;
        }
    }
    result.split = true;
    result.threshold = values[best_k];
    result.lower_max = values[best_k - 1];
    result.num_upper = static_cast<int>(n - best_k);
    result.effectiveness = total_var > 0 ? std::min(1.0, best / total_var) : 0.0;
    return result;
}

}  // namespace geotex
