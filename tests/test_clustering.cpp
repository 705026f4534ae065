#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "geometry/clustering.hpp"
#include "geometry/rand_index.hpp"

using geotex::adjusted_rand_index;
using geotex::ClusteringParams;
using geotex::ClusteringResult;
using geotex::make_clustering;

namespace {

constexpr double kTwoPi = 6.283185307179586;

/// Reproducible random numbers on every standard library: only the raw 64-bit outputs of
/// std::mt19937_64 are specified, so uniforms and normals are derived here (Box-Muller).
class Sampler {
  public:
    explicit Sampler(std::uint64_t seed) : engine_(seed) {}

    std::uint64_t raw() { return engine_(); }

    /// Uniform in (0, 1): the top 53 bits, centred in their cell so 0 never occurs.
    double uniform() { return (static_cast<double>(engine_() >> 11) + 0.5) * 0x1p-53; }

    double normal() {
        const double u1 = uniform(), u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
    }

  private:
    std::mt19937_64 engine_;
};

struct Blob {
    std::vector<double> centre;
    double spread;  ///< standard deviation in every coordinate
    int count;
};

/// Points (#points by #dimensions) with the index of the blob or ring each comes from.
struct Sample {
    Eigen::MatrixXd points;
    std::vector<int> truth;
};

Sample make_blobs(Sampler& s, const std::vector<Blob>& blobs) {
    int n = 0;
    for (const Blob& b : blobs) n += b.count;
    const auto dim = static_cast<Eigen::Index>(blobs.front().centre.size());
    Sample out{Eigen::MatrixXd(n, dim), {}};
    Eigen::Index row = 0;
    for (std::size_t g = 0; g < blobs.size(); ++g)
        for (int i = 0; i < blobs[g].count; ++i, ++row) {
            for (Eigen::Index k = 0; k < dim; ++k)
                out.points(row, k) =
                    blobs[g].centre[static_cast<std::size_t>(k)] + blobs[g].spread * s.normal();
            out.truth.push_back(static_cast<int>(g));
        }
    return out;
}

std::vector<double> random_centre(Sampler& s, int dim, double scale) {
    std::vector<double> c(static_cast<std::size_t>(dim));
    for (double& v : c) v = scale * s.normal();
    return c;
}

/// Three unit blobs of 40 points in 18-D (the paper's feature count) whose centres are
/// 5 * N(0, 1) per coordinate: about 30 apart, against within-blob distances of about 6.
Sample three_blobs_18d(Sampler& s) {
    std::vector<Blob> blobs;
    for (int g = 0; g < 3; ++g) blobs.push_back({random_centre(s, 18, 5.0), 1.0, 40});
    return make_blobs(s, blobs);
}

/// Four 2-D blobs whose spreads differ by a factor 60 and sizes by 4: the tight one sits
/// 10 spreads of its neighbour away, closer than the wide blobs' own point spacing, so no
/// single global scale separates all four; the local scale does.
Sample four_spreads(Sampler& s) {
    return make_blobs(
        s, {{{0, 0}, 0.05, 20}, {{3, 0}, 0.3, 40}, {{0, 10}, 1.5, 80}, {{22, 8}, 3.0, 60}});
}

/// Two concentric noisy rings (radii 1 and 3, 100 and 200 points): not linearly separable,
/// the classic spectral clustering example.
Sample two_rings(Sampler& s) {
    const double radii[2] = {1.0, 3.0};
    const int counts[2] = {100, 200};
    Sample out{Eigen::MatrixXd(counts[0] + counts[1], 2), {}};
    Eigen::Index row = 0;
    for (int g = 0; g < 2; ++g)
        for (int i = 0; i < counts[g]; ++i, ++row) {
            const double t = kTwoPi * s.uniform();
            out.points(row, 0) = radii[g] * std::cos(t) + 0.08 * s.normal();
            out.points(row, 1) = radii[g] * std::sin(t) + 0.08 * s.normal();
            out.truth.push_back(g);
        }
    return out;
}

/// Labels cover every point, lie in [0, num_clusters), every group is non-empty and groups
/// are numbered by their smallest member index (each new label is the next number).
void check_invariants(const ClusteringResult& r, Eigen::Index num_points) {
    REQUIRE(r.labels.size() == static_cast<std::size_t>(num_points));
    int next = 0;
    for (int l : r.labels) {
        REQUIRE(l >= 0);
        REQUIRE(l <= next);
        if (l == next) ++next;
    }
    REQUIRE(next == r.num_clusters);
    REQUIRE(r.quality.size() == r.conductance.size());
    for (double q : r.quality) {
        REQUIRE(q >= 0.0);
        REQUIRE(q <= 1.0);
    }
}

bool mentions(const geotex::Diagnostics& diagnostics, const std::string& word) {
    for (const auto& d : diagnostics)
        if (d.stage == "clustering" && d.message.find(word) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("make_clustering: well separated blobs give one group each", "[geometry][clustering]") {
    Sampler s(101);
    SECTION("three blobs in 18-D") {
        const Sample sample = three_blobs_18d(s);
        const ClusteringResult r = make_clustering(sample.points);
        check_invariants(r, sample.points.rows());
        CHECK(r.num_clusters == 3);
        CHECK(adjusted_rand_index(r.labels, sample.truth) == 1.0);
        CHECK(r.diagnostics.empty());
    }
    SECTION("three blobs in 2-D") {
        const Sample sample =
            make_blobs(s, {{{0, 0}, 1.0, 40}, {{10, 0}, 1.0, 40}, {{5, 9}, 1.0, 40}});
        const ClusteringResult r = make_clustering(sample.points);
        check_invariants(r, sample.points.rows());
        CHECK(r.num_clusters == 3);
        CHECK(adjusted_rand_index(r.labels, sample.truth) == 1.0);
    }
}

TEST_CASE("make_clustering: one Gaussian blob is one group", "[geometry][clustering]") {
    Sampler s(202);
    for (const auto& [dim, count] : std::vector<std::pair<int, int>>{{18, 40}, {2, 40}, {2, 300}}) {
        CAPTURE(dim, count);
        const Sample sample =
            make_blobs(s, {{std::vector<double>(static_cast<std::size_t>(dim), 0.0), 1.0, count}});
        const ClusteringResult r = make_clustering(sample.points);
        check_invariants(r, sample.points.rows());
        CHECK(r.num_clusters == 1);
        CHECK(r.quality.size() == 9);  // group counts 2 .. 10 were tried
    }
}

TEST_CASE("make_clustering: blobs of very different spreads and sizes are all found",
          "[geometry][clustering]") {
    Sampler s(303);
    const Sample sample = four_spreads(s);
    const ClusteringResult r = make_clustering(sample.points);
    check_invariants(r, sample.points.rows());
    CHECK(r.num_clusters == 4);
    CHECK(adjusted_rand_index(r.labels, sample.truth) == 1.0);
}

TEST_CASE("make_clustering: two concentric rings give two groups", "[geometry][clustering]") {
    Sampler s(404);
    const Sample sample = two_rings(s);
    const ClusteringResult r = make_clustering(sample.points);
    check_invariants(r, sample.points.rows());
    CHECK(r.num_clusters == 2);
    CHECK(adjusted_rand_index(r.labels, sample.truth) == 1.0);
}

TEST_CASE("make_clustering: permuting the points permutes the partition",
          "[geometry][clustering]") {
    Sampler s(505);
    const Sample sample = four_spreads(s);
    const Eigen::Index n = sample.points.rows();
    std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
    for (Eigen::Index i = n - 1; i > 0; --i)  // Fisher-Yates on raw outputs
        std::swap(order[static_cast<std::size_t>(i)],
                  order[static_cast<std::size_t>(s.raw() % static_cast<std::uint64_t>(i + 1))]);
    Eigen::MatrixXd permuted(n, sample.points.cols());
    for (Eigen::Index i = 0; i < n; ++i)
        permuted.row(i) = sample.points.row(order[static_cast<std::size_t>(i)]);

    const ClusteringResult original = make_clustering(sample.points);
    const ClusteringResult shuffled = make_clustering(permuted);
    check_invariants(shuffled, n);
    std::vector<int> original_in_new_order;
    for (Eigen::Index i = 0; i < n; ++i)
        original_in_new_order.push_back(
            original.labels[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])]);
    CHECK(shuffled.num_clusters == original.num_clusters);
    CHECK(adjusted_rand_index(shuffled.labels, original_in_new_order) == 1.0);
}

TEST_CASE("make_clustering: rescaling or shifting a feature does not change the groups",
          "[geometry][clustering]") {
    Sampler s(606);
    const Sample sample = four_spreads(s);
    const ClusteringResult reference = make_clustering(sample.points);
    for (const double k : {1e3, 1e-3, 1e6}) {
        CAPTURE(k);
        Eigen::MatrixXd changed = sample.points;
        changed.col(0) *= k;
        changed.col(1) = changed.col(1).array() * 2.5 - 40.0;
        const ClusteringResult r = make_clustering(changed);
        CHECK(r.labels == reference.labels);
    }
}

TEST_CASE("make_clustering: repeated runs are bit-identical", "[geometry][clustering]") {
    Sampler s(707);
    const Sample sample = three_blobs_18d(s);
    const ClusteringResult a = make_clustering(sample.points);
    const ClusteringResult b = make_clustering(sample.points);
    CHECK(a.labels == b.labels);
    CHECK(a.num_clusters == b.num_clusters);
    CHECK(a.quality == b.quality);  // exact comparison on purpose
    CHECK(a.conductance == b.conductance);
}

TEST_CASE("make_clustering: non-finite features throw InvalidInput", "[geometry][clustering]") {
    Sampler s(808);
    const Sample sample = make_blobs(s, {{{0, 0, 0}, 1.0, 12}});
    for (const double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()}) {
        Eigen::MatrixXd points = sample.points;
        points(5, 2) = bad;
        REQUIRE_THROWS_AS(make_clustering(points), geotex::InvalidInput);
        REQUIRE_THROWS_WITH(make_clustering(points), Catch::Contains("row 5, column 2"));
    }
}

TEST_CASE("make_clustering: parameters out of range throw InvalidInput", "[geometry][clustering]") {
    const Eigen::MatrixXd points = Eigen::MatrixXd::Random(10, 2);
    ClusteringParams p;
    p.neighbour_rank = 0;
    REQUIRE_THROWS_AS(make_clustering(points, p), geotex::InvalidInput);
    p = {};
    p.max_clusters = 0;
    REQUIRE_THROWS_AS(make_clustering(points, p), geotex::InvalidInput);
    p = {};
    p.quality_tolerance = -0.1;
    REQUIRE_THROWS_AS(make_clustering(points, p), geotex::InvalidInput);
    p = {};
    p.min_quality = 1.5;
    REQUIRE_THROWS_AS(make_clustering(points, p), geotex::InvalidInput);
    p = {};
    p.max_conductance = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_AS(make_clustering(points, p), geotex::InvalidInput);
    for (int bad : {-1, 1}) {
        p = {};
        p.max_points = bad;
        REQUIRE_THROWS_AS(make_clustering(points, p), geotex::InvalidInput);
    }
}

TEST_CASE("make_clustering: zero, one and two points", "[geometry][clustering]") {
    SECTION("no point: no group") {
        const ClusteringResult r = make_clustering(Eigen::MatrixXd(0, 18));
        CHECK(r.labels.empty());
        CHECK(r.num_clusters == 0);
        CHECK(r.quality.empty());
    }
    SECTION("one point: one group") {
        const ClusteringResult r = make_clustering(Eigen::MatrixXd::Constant(1, 18, 3.0));
        CHECK(r.labels == std::vector<int>{0});
        CHECK(r.num_clusters == 1);
    }
    SECTION("two points: one group, each is the other's only neighbour") {
        Eigen::MatrixXd points(2, 3);
        points << 0, 0, 0, 5, -1, 2;
        const ClusteringResult r = make_clustering(points);
        CHECK(r.labels == std::vector<int>{0, 0});
        CHECK(r.num_clusters == 1);
        const ClusteringResult same = make_clustering(Eigen::MatrixXd::Zero(2, 3));
        CHECK(same.labels == std::vector<int>{0, 0});
    }
}

TEST_CASE("make_clustering: groups need more points than neighbour_rank",
          "[geometry][clustering]") {
    // Two tight triples far apart. With K = 7 every local scale reaches into the other
    // triple, so nothing separates them; with K = 2 the scales stay inside.
    Eigen::MatrixXd points(6, 2);
    points << 0, 0, 0.1, 0, 0, 0.1, 10, 10, 10.1, 10, 10, 10.1;
    const ClusteringResult wide = make_clustering(points);
    check_invariants(wide, 6);
    CHECK(wide.num_clusters == 1);
    ClusteringParams p;
    p.neighbour_rank = 2;
    const ClusteringResult narrow = make_clustering(points, p);
    check_invariants(narrow, 6);
    CHECK(narrow.labels == std::vector<int>{0, 0, 0, 1, 1, 1});
}

TEST_CASE("make_clustering: max_clusters = 1 gives one group", "[geometry][clustering]") {
    Sampler s(909);
    ClusteringParams p;
    p.max_clusters = 1;
    const ClusteringResult r = make_clustering(three_blobs_18d(s).points, p);
    CHECK(r.num_clusters == 1);
    CHECK(r.quality.empty());
}

TEST_CASE("make_clustering: duplicated feature vectors", "[geometry][clustering]") {
    SECTION("two repeated vectors form two groups and are reported") {
        Eigen::MatrixXd points(40, 3);
        for (Eigen::Index i = 0; i < 40; ++i)
            points.row(i) = i % 2 ? Eigen::RowVector3d(1, 2, 3) : Eigen::RowVector3d(4, 0, 3);
        const ClusteringResult r = make_clustering(points);
        check_invariants(r, 40);
        CHECK(r.num_clusters == 2);
        for (Eigen::Index i = 0; i < 40; ++i)
            CHECK(r.labels[static_cast<std::size_t>(i)] == static_cast<int>(i % 2));
        CHECK(mentions(r.diagnostics, "duplicates"));
    }
    SECTION("all identical: one group") {
        const ClusteringResult r = make_clustering(Eigen::MatrixXd::Constant(30, 18, 0.25));
        check_invariants(r, 30);
        CHECK(r.num_clusters == 1);
    }
}

TEST_CASE("make_clustering: an isolated point joins its nearest group", "[geometry][clustering]") {
    // Three sets of 8 identical points (local scale floored: affinity 0 to anything else)
    // and one point far away, whose every affinity underflows.
    Eigen::MatrixXd points(25, 2);
    for (Eigen::Index i = 0; i < 24; ++i) {
        const auto set = static_cast<double>(i / 8);
        points.row(i) << set, set * set;
    }
    points.row(24) << -40.0, 0.0;  // nearest set: the first one
    const ClusteringResult r = make_clustering(points);
    check_invariants(r, 25);
    CHECK(r.num_clusters == 3);
    CHECK(r.labels[24] == r.labels[0]);
    CHECK(mentions(r.diagnostics, "isolated"));
}

TEST_CASE("make_clustering: up to max_points every point is clustered, as with no limit",
          "[geometry][clustering]") {
    Sampler s(1212);
    const Sample sample = three_blobs_18d(s);  // 120 points
    ClusteringParams all;
    all.max_points = 0;
    const ClusteringResult reference = make_clustering(sample.points, all);
    for (int max_points : {120, 2000}) {
        CAPTURE(max_points);
        ClusteringParams p;
        p.max_points = max_points;
        const ClusteringResult r = make_clustering(sample.points, p);
        CHECK(r.num_landmarks == 0);
        CHECK(r.labels == reference.labels);
        CHECK(r.quality == reference.quality);
        CHECK(r.conductance == reference.conductance);
        CHECK_FALSE(mentions(r.diagnostics, "landmark"));
    }
}

namespace {

/// make_clustering of `points` with `landmarks` as max_points, checked for the invariants and
/// for having used that many landmarks.
ClusteringResult clustered_with_landmarks(const Eigen::MatrixXd& points, int landmarks) {
    ClusteringParams p;
    p.max_points = landmarks;
    ClusteringResult r = make_clustering(points, p);
    check_invariants(r, points.rows());
    CHECK(r.num_landmarks == landmarks);
    return r;
}

}  // namespace

TEST_CASE(
    "make_clustering: above max_points the landmarks are clustered and the others join "
    "their nearest",
    "[geometry][clustering]") {
    Sampler s(1313);
    SECTION("three blobs in 18-D, 3000 points, 300 landmarks") {
        std::vector<Blob> blobs;
        for (int g = 0; g < 3; ++g) blobs.push_back({random_centre(s, 18, 5.0), 1.0, 1000});
        const Sample sample = make_blobs(s, blobs);
        const ClusteringResult r = clustered_with_landmarks(sample.points, 300);
        CHECK(r.num_clusters == 3);
        CHECK(adjusted_rand_index(r.labels, sample.truth) == 1.0);
        CHECK(mentions(r.diagnostics, "300 landmarks"));
    }
    SECTION("two concentric rings, 1200 points, 300 landmarks: groups that are not blobs") {
        // The rings of two_rings (a third of the points on the inner one) four times as
        // many, each point's ring drawn at random, so the landmarks (every fourth point)
        // fall on both.
        Sample rings{Eigen::MatrixXd(1200, 2), {}};
        for (Eigen::Index i = 0; i < rings.points.rows(); ++i) {
            const int g = s.uniform() < 1.0 / 3.0 ? 0 : 1;
            const double radius = g == 0 ? 1.0 : 3.0;
            const double t = kTwoPi * s.uniform();
            rings.points(i, 0) = radius * std::cos(t) + 0.08 * s.normal();
            rings.points(i, 1) = radius * std::sin(t) + 0.08 * s.normal();
            rings.truth.push_back(g);
        }
        const ClusteringResult r = clustered_with_landmarks(rings.points, 300);
        CHECK(r.num_clusters == 2);
        CHECK(adjusted_rand_index(r.labels, rings.truth) == 1.0);
    }
    SECTION("a kind rarer than (neighbour_rank + 1) n / m points joins its nearest group") {
        // Blobs of 1485, 1485 and 30 points in 18-D, in that order, so that the evenly spaced
        // landmarks sample each in proportion. With 300 landmarks the rare blob holds 3 of
        // them, fewer than neighbour_rank + 1 (8): their local scales reach into the other
        // blobs and the blob joins one (clustering.cpp, "Landmarks"). With 1000 it holds 10
        // and stands apart, as it does when every point is clustered (not run here: 8 s).
        std::vector<Blob> blobs;
        for (int count : {1485, 1485, 30}) blobs.push_back({random_centre(s, 18, 5.0), 1.0, count});
        const Sample sample = make_blobs(s, blobs);
        const ClusteringResult few = clustered_with_landmarks(sample.points, 300);
        CHECK(few.num_clusters == 2);
        std::vector<int> big_blobs = sample.truth;  // the rare blob counted as a big one's
        const int joined = few.labels[2970] == few.labels[0] ? 0 : 1;
        for (std::size_t i = 2970; i < 3000; ++i) big_blobs[i] = joined;
        CHECK(adjusted_rand_index(few.labels, big_blobs) == 1.0);
        const ClusteringResult enough = clustered_with_landmarks(sample.points, 1000);
        CHECK(enough.num_clusters == 3);
        CHECK(adjusted_rand_index(enough.labels, sample.truth) == 1.0);
    }
    SECTION("one point more than max_points: every point but one is a landmark") {
        const Sample sample = three_blobs_18d(s);
        const ClusteringResult r = clustered_with_landmarks(sample.points, 119);
        CHECK(adjusted_rand_index(r.labels, sample.truth) == 1.0);
    }
}
