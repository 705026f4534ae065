/// Adjusted Rand index (Hubert & Arabie 1985). With the contingency table n_ij (items with
/// label i in a and j in b), row sums a_i, column sums b_j and N items:
///     index    = sum_ij C(n_ij, 2)
///     expected = sum_i C(a_i, 2) sum_j C(b_j, 2) / C(N, 2)
///     maximum  = (sum_i C(a_i, 2) + sum_j C(b_j, 2)) / 2
///     ARI      = (index - expected) / (maximum - expected).
/// With A = sum_i C(a_i, 2), B = sum_j C(b_j, 2) and T = C(N, 2), both in [0, T],
/// maximum - expected >= sqrt(AB) - AB/T >= 0, with equality only for A = B = 0 (both all
/// singletons) or A = B = T (both one group): identical partitions, value 1.

#include "geometry/rand_index.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

#include "common/errors.hpp"

namespace geotex {
namespace {

/// Sum over runs of equal consecutive values of C(run length, 2); `v` must be sorted.
template <typename T>
std::int64_t pairs_in_runs(const std::vector<T>& v) {
    std::int64_t total = 0;
    for (std::size_t start = 0; start < v.size();) {
        std::size_t end = start;
        while (end < v.size() && v[end] == v[start]) ++end;
        const auto len = static_cast<std::int64_t>(end - start);
        total += len * (len - 1) / 2;
        start = end;
    }
    return total;
}

}  // namespace

double adjusted_rand_index(const std::vector<int>& a, const std::vector<int>& b) {
    if (a.size() != b.size())
        throw InvalidInput("adjusted_rand_index: the partitions have " + std::to_string(a.size()) +
                           " and " + std::to_string(b.size()) +
                           " labels; give one label per item in both");
    std::vector<std::pair<int, int>> joint(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) joint[i] = {a[i], b[i]};
    std::vector<int> sa = a, sb = b;
    std::sort(joint.begin(), joint.end());
    std::sort(sa.begin(), sa.end());
    std::sort(sb.begin(), sb.end());

    const std::int64_t index = pairs_in_runs(joint);
    const std::int64_t sum_a = pairs_in_runs(sa);
    const std::int64_t sum_b = pairs_in_runs(sb);
    const auto n = static_cast<std::int64_t>(a.size());
    const std::int64_t total = n * (n - 1) / 2;
    // The degenerate cases are exactly A = B in {0, T}; integer tests avoid any rounding.
    if (sum_a == sum_b && (sum_a == 0 || sum_a == total)) return 1.0;

    const double expected =
        static_cast<double>(sum_a) * static_cast<double>(sum_b) / static_cast<double>(total);
    const double maximum = 0.5 * (static_cast<double>(sum_a) + static_cast<double>(sum_b));
    return (static_cast<double>(index) - expected) / (maximum - expected);
}

}  // namespace geotex
