#pragma once
/// Otsu's threshold (Otsu 1979), computed exactly on the samples rather than on a
/// histogram: no bin count to choose, and the same answer at any depth range.

#include <vector>

namespace geotex {

struct OtsuResult {
    double threshold = 0;      ///< upper class = samples >= threshold; +inf when no split exists
    double lower_max = 0;      ///< largest sample of the lower class
    double effectiveness = 0;  ///< between-class variance / total variance, in [0, 1]
    int num_upper = 0;         ///< samples in the upper class
    bool split = false;        ///< false when there are fewer than two distinct values
};

/// Splits `values` into two classes so that the between-class variance is largest (ties:
/// the lowest threshold). O(n log n), sorted in parallel from 65,536 values on, with the same
/// result for any thread count (-0.0 is taken as 0.0). Throws InvalidInput on a non-finite
/// value.
OtsuResult otsu_threshold(std::vector<double> values);

}  // namespace geotex
