#pragma once
/// Otsu's threshold (Otsu 1979), computed exactly on the samples rather than on a
/// histogram: no bin count to choose, and the same answer at any depth range.

#include <cstddef>
#include <string>
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

/// Values in ascending order read a block at a time, able to start again from the first: one
/// tile's sorted depths in a file, so that Otsu's threshold over a whole scan's depths needs a
/// block of each tile's in memory, not all of them (otsu_threshold_merged).
class SortedValues {
  public:
    virtual ~SortedValues() = default;
    /// How many values there are.
    virtual std::size_t size() const = 0;
    /// Starts again from the first value.
    virtual void restart() = 0;
    /// Copies the next values, at most `max`, to `out`; returns how many (0 after the last).
    /// Throws InvalidInput when what it reads is damaged.
    virtual std::size_t next(double* out, std::size_t max) = 0;
    /// The file the values come from, which errors about them name; empty: none.
    virtual std::string name() const { return {}; }
};

/// otsu_threshold of every value of every run and `zeros` more 0.0 values, bit for bit, in
/// two passes over the runs merged, holding a block of each. Each run must be ascending,
/// finite and without -0.0; throws InvalidInput where one is not, naming the run by its index
/// and its file (SortedValues::name).
OtsuResult otsu_threshold_merged(const std::vector<SortedValues*>& runs, std::size_t zeros = 0);

}  // namespace geotex
