#include <tbb/global_control.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <random>

#include "common/errors.hpp"
#include "geometry/otsu.hpp"

using namespace geotex;

namespace {
// Between-class variance of the split {x < t} | {x >= t}, straight from the definition.
double between_variance(const std::vector<double>& x, double t) {
    double n0 = 0, n1 = 0, s0 = 0, s1 = 0;
    for (double v : x) (v < t ? (n0 += 1, s0 += v) : (n1 += 1, s1 += v));
    if (n0 == 0 || n1 == 0) return 0;
    const double n = n0 + n1, m0 = s0 / n0, m1 = s1 / n1;
    return n0 / n * n1 / n * (m0 - m1) * (m0 - m1);
}
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
}  // namespace

TEST_CASE("otsu_threshold: hand-computed split of a small sample", "[geometry][otsu]") {
    // {1,2,3} | {10,11,12}: means 2 and 11, w0 = w1 = 1/2, between = 81/4; any other split
    // mixes the groups and scores less (e.g. {1,2} | {3,10,11,12}: 1/3*2/3*(1.5-9)^2 = 12.5).
    const OtsuResult r = otsu_threshold({12, 1, 11, 3, 10, 2});
    REQUIRE(r.split);
    CHECK(r.threshold == 10);
    CHECK(r.lower_max == 3);
    CHECK(r.num_upper == 3);
    CHECK(r.effectiveness == Approx(81.0 / 4 / (81.0 / 4 + 2.0 / 3)));
}

TEST_CASE("otsu_threshold: bimodal sample split between its modes", "[geometry][otsu]") {
    std::mt19937_64 rng(3);
    std::vector<double> x;
    for (int i = 0; i < 3000; ++i) x.push_back(0.1 * uniform(rng));        // mode at [0, 0.1)
    for (int i = 0; i < 1000; ++i) x.push_back(0.8 + 0.1 * uniform(rng));  // mode at [0.8, 0.9)
    const OtsuResult r = otsu_threshold(x);
    CHECK(r.threshold >= 0.8);
    CHECK(r.lower_max < 0.1);
    CHECK(r.num_upper == 1000);
    CHECK(r.effectiveness > 0.95);
}

TEST_CASE("otsu_threshold: maximises the between-class variance over all splits",
          "[geometry][otsu]") {
    std::mt19937_64 rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<double> x;
        const int n = 5 + static_cast<int>(rng() % 60);
        for (int i = 0; i < n; ++i) x.push_back(std::floor(uniform(rng) * 20) / 4);  // ties
        const OtsuResult r = otsu_threshold(x);
        if (!r.split) continue;
        const double best = between_variance(x, r.threshold);
        for (double t : x) CHECK(between_variance(x, t) <= best * (1 + 1e-12) + 1e-15);
    }
}

TEST_CASE("otsu_threshold: no split for constant or tiny samples; rejects NaN",
          "[geometry][otsu]") {
    CHECK_FALSE(otsu_threshold({}).split);
    CHECK_FALSE(otsu_threshold({2.0}).split);
    const OtsuResult c = otsu_threshold({3, 3, 3});
    CHECK_FALSE(c.split);
    CHECK(std::isinf(c.threshold));
    REQUIRE_THROWS_AS(otsu_threshold({1, std::numeric_limits<double>::quiet_NaN()}), InvalidInput);
}

TEST_CASE("otsu_threshold: invariant to rescaling the values by 10^k", "[geometry][otsu]") {
    const std::vector<double> x = {0.1, 0.2, 0.25, 0.9, 1.0, 1.3, 0.05};
    const OtsuResult r = otsu_threshold(x);
    for (double k : {1e-6, 1e6}) {
        std::vector<double> y;
        for (double v : x) y.push_back(v * k);
        CHECK(otsu_threshold(y).num_upper == r.num_upper);
    }
}

TEST_CASE("otsu_threshold: a large sample sorted in parallel gives the serial answer; -0.0 is 0.0",
          "[geometry][otsu]") {
    // Half zeros, as a depth map whose unmoved vertices have depth 0, and two modes above.
    std::mt19937_64 rng(7);
    std::vector<double> x(300000, 0.0);
    for (std::size_t i = 0; i < x.size(); i += 2) x[i] = (i % 3 ? 1.0 : 3.0) + uniform(rng);
    const auto with_threads = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return otsu_threshold(x);
    };
    const OtsuResult one = with_threads(1), two = with_threads(2);
    CHECK(one.threshold == two.threshold);
    CHECK(one.num_upper == two.num_upper);
    CHECK(one.effectiveness == two.effectiveness);
    CHECK(one.threshold > 1.0);
    // The split between the negative values and the zeros lands on a zero: +0.0, whichever
    // zero the sort puts first.
    const OtsuResult zero = otsu_threshold({-1.0, -1.0, -0.0, 0.0, -0.0});
    REQUIRE(zero.split);
    CHECK(zero.threshold == 0.0);
    CHECK(!std::signbit(zero.threshold));
}

namespace {

// A run held in memory, handing out at most `step` values a call, so that the merge's blocks
// are refilled at places that do not line up with its own.
class VectorRun final : public SortedValues {
  public:
    explicit VectorRun(std::vector<double> values, std::size_t step = 1000, long extra = 0)
        : values_(std::move(values)), step_(step), extra_(extra) {}
    std::size_t size() const override {
        return static_cast<std::size_t>(static_cast<long>(values_.size()) + extra_);
    }
    void restart() override { at_ = 0; }
    std::size_t next(double* out, std::size_t max) override {
        const std::size_t n = std::min({max, step_, values_.size() - at_});
        std::copy(values_.begin() + static_cast<long>(at_),
                  values_.begin() + static_cast<long>(at_ + n), out);
        at_ += n;
        return n;
    }

  private:
    std::vector<double> values_;
    std::size_t step_, at_ = 0;
    long extra_;  // a size that lies by this much
};

bool same_result(const OtsuResult& a, const OtsuResult& b) {
    const auto bits = [](double x) {
        std::uint64_t u;
        std::memcpy(&u, &x, sizeof u);
        return u;
    };
    return a.split == b.split && bits(a.threshold) == bits(b.threshold) &&
           bits(a.lower_max) == bits(b.lower_max) &&
           bits(a.effectiveness) == bits(b.effectiveness) && a.num_upper == b.num_upper;
}

}  // namespace

TEST_CASE("otsu_threshold_merged: sorted runs and zeros give the bits of one sort of them all",
          "[geometry][otsu]") {
    std::mt19937_64 rng(5);
    for (int trial = 0; trial < 12; ++trial) {
        // Runs of a few to 20,000 values (past the merge's blocks of 4096), some empty, with
        // values shared between runs, zeros in the runs and besides them.
        const int num_runs = 1 + static_cast<int>(rng() % 9);
        std::vector<std::vector<double>> runs(num_runs);
        std::vector<double> all;
        for (auto& run : runs) {
            const int n =
                trial % 3 == 0 ? static_cast<int>(rng() % 20000) : static_cast<int>(rng() % 50);
            for (int i = 0; i < n; ++i) {
                const double u = uniform(rng);
                run.push_back(u < 0.4 ? 0.0 : u < 0.6 ? std::floor(u * 40) / 8 : 3 * u);
            }
            std::sort(run.begin(), run.end());
            all.insert(all.end(), run.begin(), run.end());
        }
        const std::size_t zeros = rng() % 3 == 0 ? 0 : rng() % 500;
        all.insert(all.end(), zeros, 0.0);
        std::vector<std::unique_ptr<VectorRun>> held;
        std::vector<SortedValues*> given;
        for (std::size_t k = 0; k < runs.size(); ++k) {
            held.push_back(std::make_unique<VectorRun>(runs[k], 1 + rng() % 5000));
            given.push_back(held.back().get());
        }
        const OtsuResult merged = otsu_threshold_merged(given, zeros);
        const OtsuResult sorted = otsu_threshold(all);
        CHECK(same_result(merged, sorted));
        if (all.size() > 100) CHECK(merged.split);
    }
}

TEST_CASE("otsu_threshold: non-negative values of any magnitude are ordered as a sort orders them",
          "[geometry][otsu]") {
    // Samples of 512 values up to the parallel sort's size are sorted by their bits when none
    // is negative. Values from subnormals to 2^500 (so that no square overflows), repeats,
    // zeros and -0.0, so that every digit of the bits differs somewhere. One sorted run through
    // the merge, which does not sort, must give the same bits: the running sums follow the
    // order.
    std::mt19937_64 rng(13);
    for (int trial = 0; trial < 8; ++trial) {
        std::vector<double> x;
        const int n = 512 + static_cast<int>(rng() % 30000);  // the radix sort's sizes
        for (int i = 0; i < n; ++i) {
            const double u = uniform(rng);
            const int kind = static_cast<int>(rng() % 5);
            const int exponent = kind == 2 ? -1074 + static_cast<int>(rng() % 60)  // subnormal
                                           : static_cast<int>(rng() % 1500) - 1000;
            x.push_back(kind == 0   ? 0.0
                        : kind == 1 ? -0.0
                        : kind == 4 ? std::floor(u * 8) / 4  // repeats
                                    : std::ldexp(u, exponent));
        }
        std::vector<double> sorted = x;
        for (double& v : sorted) v = v == 0 ? 0.0 : v;
        std::sort(sorted.begin(), sorted.end());
        VectorRun run(sorted, 777);
        const OtsuResult r = otsu_threshold(x);
        CHECK(r.split);
        CHECK(std::isfinite(r.effectiveness));
        CHECK(same_result(r, otsu_threshold_merged({&run})));
    }
}

TEST_CASE("otsu_threshold_merged: no split for fewer than two values or one value repeated",
          "[geometry][otsu]") {
    CHECK_FALSE(otsu_threshold_merged({}, 0).split);
    CHECK_FALSE(otsu_threshold_merged({}, 7).split);
    VectorRun one({2.0});
    CHECK_FALSE(otsu_threshold_merged({&one}, 0).split);
    VectorRun same({0.0, 0.0});
    CHECK_FALSE(otsu_threshold_merged({&same}, 3).split);
    VectorRun two({1.0});
    const OtsuResult r = otsu_threshold_merged({&two}, 1);
    REQUIRE(r.split);
    CHECK(r.threshold == 1.0);
    CHECK(r.num_upper == 1);
}

TEST_CASE("otsu_threshold_merged: a damaged run is refused, naming it", "[geometry][otsu]") {
    VectorRun good({0.0, 1.0, 2.0});
    VectorRun descending({0.0, 2.0, 1.0});
    CHECK_THROWS_WITH(otsu_threshold_merged({&good, &descending}),
                      "Otsu threshold: sorted run 2 is not ascending");
    VectorRun negative_zero({-0.0, 1.0});
    CHECK_THROWS_WITH(otsu_threshold_merged({&negative_zero, &good}),
                      "Otsu threshold: sorted run 1 holds -0.0");
    VectorRun nan({0.0, std::numeric_limits<double>::quiet_NaN()});
    CHECK_THROWS_WITH(otsu_threshold_merged({&good, &nan}),
                      "Otsu threshold: sorted run 2 holds a value that is not finite");
    VectorRun short_run({0.0, 1.0}, 1000, 1);
    CHECK_THROWS_WITH(otsu_threshold_merged({&short_run}),
                      "Otsu threshold: sorted run 1 gives fewer values than its size");
    VectorRun long_run({0.0, 1.0, 2.0}, 1000, -1);
    CHECK_THROWS_WITH(otsu_threshold_merged({&long_run}),
                      "Otsu threshold: sorted run 1 gives more values than its size");
    CHECK_THROWS_WITH(otsu_threshold_merged({&good, nullptr}),
                      "Otsu threshold: sorted run 2 is missing");
}
