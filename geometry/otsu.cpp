#include "geometry/otsu.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"

namespace geotex {

namespace {

// Below this many values a sort is not worth splitting over threads.
constexpr std::size_t kParallelSortSize = std::size_t{1} << 16;
// Below this many values std::sort beats the radix sort below, whose every pass clears and
// sums its 2048 counts (a standalone measure: at 64 values 1.5 against 10 us, even at about
// 256, 4 times faster at 4096).
constexpr std::size_t kRadixSortSize = 512;

// Sorts finite values that are all >= 0, with no -0.0, ascending: the same sequence as
// std::sort. The bits of such a double, read as an unsigned integer, order as the values do
// (the sign bit is clear, the exponent field stands above the fraction), so a radix sort of
// the bits needs no comparison: six passes of 11 bits, each skipped when every value has the
// same digit there (depths share most of their exponent bits). Written here because neither
// the standard library nor TBB has a radix sort, and std::sort of each seed's disc was half
// of the texel stage at large scales: on sphere-1 level 7 at 16%, where a disc of 2r holds a
// third of the sphere, the stage takes 0.12 s instead of 0.24.
void radix_sort_non_negative(std::vector<double>& values) {
    constexpr int kDigitBits = 11;
    constexpr std::uint64_t kMask = (std::uint64_t{1} << kDigitBits) - 1;
    const auto digit = [](double v, int shift) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        return (bits >> shift) & kMask;
    };
    // One buffer beside the values and the counts on the stack: this runs once per seed, inside
    // a parallel loop. Counts fit 32 bits, as the values are fewer than kParallelSortSize.
    std::vector<double> moved(values.size());
    std::array<std::uint32_t, kMask + 1> start;
    const auto n = static_cast<std::uint32_t>(values.size());
    for (int shift = 0; shift < 64; shift += kDigitBits) {
        start.fill(0);
        for (double v : values) ++start[digit(v, shift)];
        if (start[digit(values.front(), shift)] == n) continue;  // one digit: no move
        std::uint32_t sum = 0;
        for (std::uint32_t& s : start) sum += std::exchange(s, sum);
        for (double v : values) moved[start[digit(v, shift)]++] = v;
        values.swap(moved);
    }
}

}  // namespace

namespace {

// Otsu's split of n values that each(fn) hands to fn in ascending order, as otsu_threshold
// defines it; each is called twice, and must give the same values both times.
template <class Each>
OtsuResult otsu_of_sorted(std::size_t n, Each&& each) {
    OtsuResult result;
    result.threshold = std::numeric_limits<double>::infinity();
    if (n < 2) return result;
    // Shift by the mean so the running sums stay well conditioned.
    double mean = 0, first = 0, last = 0;
    bool started = false;
    each([&](double v) {
        if (!started) first = v;
        started = true;
        last = v;
        mean += v;
    });
    if (first == last) return result;
    mean /= static_cast<double>(n);

    // With values centred on their mean, the between-class variance of the split
    // [0,k) | [k,n) is w0 w1 (m0 - m1)^2 = S0^2 / (k (n - k)), where S0 is the centred sum
    // of the lower class (the upper class sums to -S0). The total variance sums in the same
    // pass: each sum keeps its own order, so the pass gives what two would.
    double total_var = 0, best = -1, s0 = 0, previous = 0;
    std::size_t k = 0, best_k = 0;
    const double nn = static_cast<double>(n);
    each([&](double v) {
        total_var += (v - mean) * (v - mean);
        if (k > 0) {
            s0 += previous - mean;
            if (v != previous) {  // only split between distinct values
                const double kk = static_cast<double>(k);
                const double between = s0 * s0 / (kk * (nn - kk));
                if (between > best) {
                    best = between;
                    best_k = k;
                    result.threshold = v;
                    result.lower_max = previous;
                }
            }
        }
        previous = v;
        ++k;
    });
    total_var /= nn;
    result.split = true;
    result.num_upper = static_cast<int>(n - best_k);
    result.effectiveness = total_var > 0 ? std::min(1.0, best / total_var) : 0.0;
    return result;
}

}  // namespace

OtsuResult otsu_threshold(std::vector<double> values) {
    bool negative = false;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i]))
            throw InvalidInput("Otsu threshold: value " + std::to_string(i) + " is not finite");
        // -0.0 as 0.0: equal values then have equal bits, and every sort gives one sequence.
        if (values[i] == 0) values[i] = 0.0;
        negative = negative || values[i] < 0;
    }
    // A whole mesh's depths (tens of millions at level 11) are most of a texel job's sorting;
    // a seed's disc, sorted inside a parallel loop, stays on its thread.
    if (values.size() >= kParallelSortSize)
        detail::parallel_sort(values);
    else if (!negative && values.size() >= kRadixSortSize)
        radix_sort_non_negative(values);
    else
        std::sort(values.begin(), values.end());
    return otsu_of_sorted(values.size(), [&](auto&& take) {
        for (double v : values) take(v);
    });
}

namespace {

// `count` zeros as a run, for the vertices that are in no tile's part.
class Zeros final : public SortedValues {
  public:
    explicit Zeros(std::size_t count) : count_(count) {}
    std::size_t size() const override { return count_; }
    void restart() override { given_ = 0; }
    std::size_t next(double* out, std::size_t max) override {
        const std::size_t n = std::min(max, count_ - given_);
        std::fill(out, out + n, 0.0);
        given_ += n;
        return n;
    }

  private:
    std::size_t count_ = 0, given_ = 0;
};

// One run being merged: its block in hand and where the merge is in it.
struct Cursor {
    SortedValues* run = nullptr;
    std::size_t index = 0;  // the run's place in the caller's list, for messages
    std::vector<double> block;
    std::size_t at = 0, filled = 0, read = 0;
    double last = -std::numeric_limits<double>::infinity();

    // Whether the run has a value at `at`, reading its next block when this one is used up.
    bool has_value() {
        if (at < filled) return true;
        filled = run->next(block.data(), block.size());
        at = 0;
        read += filled;
        if (read > run->size()) fail("gives more values than its size");
        for (std::size_t i = 0; i < filled; ++i) {
            const double v = block[i];
            if (!std::isfinite(v)) fail("holds a value that is not finite");
            if (v == 0 && std::signbit(v)) fail("holds -0.0");
            if (v < last) fail("is not ascending");
            last = v;
        }
        if (filled == 0 && read != run->size()) fail("gives fewer values than its size");
        return filled > 0;
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw InvalidInput("Otsu threshold: sorted run " + std::to_string(index + 1) + " " + what,
                           run->name());
    }
};

// Values per run held by the merge.
constexpr std::size_t kMergeBlock = 4096;

}  // namespace

OtsuResult otsu_threshold_merged(const std::vector<SortedValues*>& runs, std::size_t zeros) {
    Zeros zero_run(zeros);
    std::vector<Cursor> cursors;
    std::size_t n = 0;
    for (std::size_t i = 0; i <= runs.size(); ++i) {
        SortedValues* run = i < runs.size() ? runs[i] : &zero_run;
        if (!run)
            throw InvalidInput("Otsu threshold: sorted run " + std::to_string(i + 1) +
                               " is missing");
        n += run->size();
        cursors.push_back({run, i, std::vector<double>(kMergeBlock)});
    }
    // A pass merges the runs through a tree of losers (Knuth, TAOCP vol. 3, 5.4.1): each value
    // costs one comparison a level on the path of the run it came from, where a heap would pop
    // and push it. Equal values have equal bits, so
    // whichever run gives an equal value first, the sequence is the one a sort gives.
    std::size_t leaves = 1;
    while (leaves < cursors.size()) leaves *= 2;
    constexpr double kSpent = std::numeric_limits<double>::infinity();  // no value is infinite
    std::vector<double> head(leaves);  // each run's next value, or kSpent
    std::vector<std::size_t> loser(leaves), winner(2 * leaves);
    // Without branches: which run's value comes first is a coin toss where the runs interleave,
    // and a mispredicted branch a level cost more than the comparison.
    const auto before = [&](std::size_t a, std::size_t b) {
        const double x = head[a], y = head[b];
        return static_cast<bool>(static_cast<int>(x < y) |
                                 (static_cast<int>(x == y) & static_cast<int>(a < b)));
    };
    const auto pass = [&](auto&& take) {
        for (std::size_t c = 0; c < leaves; ++c) {
            head[c] = kSpent;
            if (c >= cursors.size()) continue;
            Cursor& cur = cursors[c];
            cur.run->restart();
            cur.at = cur.filled = cur.read = 0;
            cur.last = -std::numeric_limits<double>::infinity();
            if (cur.has_value()) head[c] = cur.block[0];
        }
        // The smallest value first, from every run in turn without the tree: in a depth map it
        // is the 0 of every vertex that the oriented rule left in place.
        const double least = *std::min_element(head.begin(), head.end());
        for (std::size_t c = 0; c < cursors.size() && least != kSpent; ++c) {
            Cursor& cur = cursors[c];
            while (head[c] == least) {
                take(least);
                ++cur.at;
                head[c] = cur.has_value() ? cur.block[cur.at] : kSpent;
            }
        }
        for (std::size_t c = 0; c < leaves; ++c) winner[leaves + c] = c;
        for (std::size_t node = leaves - 1; node >= 1; --node) {
            const std::size_t a = winner[2 * node], b = winner[2 * node + 1];
            winner[node] = before(a, b) ? a : b;
            loser[node] = before(a, b) ? b : a;
        }
        std::size_t top = winner[1];
        while (head[top] != kSpent) {
            Cursor& cur = cursors[top];
            take(head[top]);
            ++cur.at;
            head[top] = cur.has_value() ? cur.block[cur.at] : kSpent;
            // The run's next value plays the losers on its way up.
            for (std::size_t node = (leaves + top) / 2; node >= 1; node /= 2) {
                const std::size_t other = loser[node];
                const bool swap = before(other, top);
                loser[node] = swap ? top : other;
                top = swap ? other : top;
            }
        }
    };
    return otsu_of_sorted(n, pass);
}

}  // namespace geotex
