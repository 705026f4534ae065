#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
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
