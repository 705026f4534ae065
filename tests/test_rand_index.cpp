#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "common/errors.hpp"
#include "geometry/rand_index.hpp"

using geotex::adjusted_rand_index;

namespace {

/// `count` labels in [0, num_labels) from the raw 64-bit outputs of a fixed-seed engine
/// (std distributions differ between standard libraries; the modulo bias is ~1e-18).
std::vector<int> random_labels(std::mt19937_64& engine, int count, int num_labels) {
    std::vector<int> labels(static_cast<std::size_t>(count));
    for (int& l : labels) l = static_cast<int>(engine() % static_cast<std::uint64_t>(num_labels));
    return labels;
}

}  // namespace

TEST_CASE("adjusted_rand_index: identical partitions give exactly 1", "[geometry][clustering]") {
    const std::vector<int> a{0, 0, 1, 1, 1, 2, 3, 3};
    CHECK(adjusted_rand_index(a, a) == 1.0);
    // Same partition under other names, including negative ones.
    CHECK(adjusted_rand_index(a, {-5, -5, 7, 7, 7, 0, 42, 42}) == 1.0);

    SECTION("degenerate cases, where the index is 0/0, are defined as 1") {
        CHECK(adjusted_rand_index({}, {}) == 1.0);
        CHECK(adjusted_rand_index({4}, {-1}) == 1.0);
        CHECK(adjusted_rand_index({2, 2, 2, 2}, {9, 9, 9, 9}) == 1.0);  // one group each
        CHECK(adjusted_rand_index({0, 1, 2, 3}, {3, 1, 0, 2}) == 1.0);  // all singletons
    }
}

TEST_CASE("adjusted_rand_index: matches hand-computed values", "[geometry][clustering]") {
    SECTION("six items") {
        // a = {0,0,0,1,1,1}, b = {0,0,1,1,2,2}. Contingency table (rows a, columns b):
        //     [2 1 0]
        //     [0 1 2]
        // index    = C(2,2) + C(2,2) = 2
        // sum_a    = C(3,2) + C(3,2) = 6,   sum_b = 3 * C(2,2) = 3,   C(6,2) = 15
        // expected = 6 * 3 / 15 = 1.2,      maximum = (6 + 3) / 2 = 4.5
        // ARI      = (2 - 1.2) / (4.5 - 1.2) = 0.8 / 3.3 = 8/33
        const double ari = adjusted_rand_index({0, 0, 0, 1, 1, 1}, {0, 0, 1, 1, 2, 2});
        CHECK(ari == Approx(8.0 / 33.0).epsilon(1e-14));
    }
    SECTION("four items crossing, worse than chance") {
        // a = {0,0,1,1}, b = {0,1,0,1}: every cell is 1, so index = 0; sum_a = sum_b = 2,
        // C(4,2) = 6, expected = 4/6, maximum = 2, ARI = (0 - 2/3) / (2 - 2/3) = -1/2.
        CHECK(adjusted_rand_index({0, 0, 1, 1}, {0, 1, 0, 1}) == Approx(-0.5).epsilon(1e-14));
    }
    SECTION("one group against all singletons") {
        // sum_a = C(5,2) = 10 = C(5,2), sum_b = 0: expected = 0, index = 0, maximum = 5.
        CHECK(adjusted_rand_index({1, 1, 1, 1, 1}, {0, 1, 2, 3, 4}) == 0.0);
    }
}

TEST_CASE("adjusted_rand_index: invariant under renaming and symmetric", "[geometry][clustering]") {
    std::mt19937_64 engine(20190611);
    const std::vector<int> a = random_labels(engine, 1000, 7);
    const std::vector<int> b = random_labels(engine, 1000, 4);
    std::vector<int> renamed = a;
    for (int& l : renamed) l = 100 - 37 * l;  // injective, partly negative
    const double ari = adjusted_rand_index(a, b);
    CHECK(adjusted_rand_index(renamed, b) == ari);
    CHECK(adjusted_rand_index(b, a) == Approx(ari).margin(1e-15));
}

TEST_CASE("adjusted_rand_index: independent random partitions give about 0",
          "[geometry][clustering]") {
    std::mt19937_64 engine(1985);
    const std::vector<int> a = random_labels(engine, 10000, 10);
    const std::vector<int> b = random_labels(engine, 10000, 6);
    // Under independence the ARI has mean 0 and a standard deviation of about 1e-4 for
    // 10,000 items and these label counts (measured over seeds); 2e-3 is a wide margin
    // that a biased formula (e.g. the unadjusted Rand index, ~0.75 here) cannot meet.
    CHECK(std::abs(adjusted_rand_index(a, b)) < 2e-3);
}

TEST_CASE("adjusted_rand_index: partitions of different sizes throw InvalidInput",
          "[geometry][clustering]") {
    REQUIRE_THROWS_AS(adjusted_rand_index({0, 1, 1}, {0, 1}), geotex::InvalidInput);
}
