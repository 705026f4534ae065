#include <catch2/catch.hpp>
#include <cmath>

#include "common/errors.hpp"
#include "geometry/depth_map.hpp"
#include "geometry/texels.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

struct Run {
    Mesh mesh;
    MeshTopology topology;
    DepthMap depth;
    TexelSet texels;
};

Run run(Mesh m, double radius, DetailOrientation o = DetailOrientation::Positive,
        double merge = 0.5) {
    Run r;
    r.mesh = std::move(m);
    r.topology = make_topology(r.mesh);
    const MeshMetrics mm = make_mesh_metrics(r.mesh, r.topology);
    SmoothingParams sp;
    sp.radius = radius;
    r.depth = make_depth_map(r.mesh, mm.vertex_normal,
                             make_smoothed_surface(r.mesh, r.topology, mm, sp), o);
    TexelParams tp;
    tp.radius = radius;
    tp.merge_overlap = merge;
    r.texels = make_texels(r.mesh, r.topology, r.depth, tp);
    return r;
}

double plateau(double x, double y, double cx, double cy, double h, double a) {
    const double d = std::hypot(x - cx, y - cy) - a;
    return h * std::max(0.0, std::min(1.0, 0.5 - d / 0.01));
}

// Invariants every texel set keeps.
void check_invariants(const Run& r) {
    std::vector<int> seen(r.mesh.num_faces(), -1);
    for (std::size_t i = 0; i < r.texels.texels.size(); ++i) {
        const Texel& t = r.texels.texels[i];
        CHECK(std::is_sorted(t.faces.begin(), t.faces.end()));
        for (int f : t.faces) {
            CHECK(seen[f] == -1);  // each face in at most one texel
            seen[f] = static_cast<int>(i);
            CHECK(r.texels.face_texel[f] == static_cast<int>(i));
        }
        if (i > 0) CHECK(r.texels.texels[i - 1].faces.front() < t.faces.front());
    }
    for (int f = 0; f < r.mesh.num_faces(); ++f) CHECK(r.texels.face_texel[f] == seen[f]);
}

}  // namespace

// Bumps of radius up to 0.75 r, like the synthetic benchmark's big discs: a plateau much
// wider than the disc is no longer salient at its centre (its disc mean sits on it).
TEST_CASE("make_texels: three separated bumps give three texels", "[geometry][texels]") {
    const double h = 0.02;
    auto height = [&](double x, double y) {
        return plateau(x, y, -0.25, -0.2, h, 0.05) + plateau(x, y, 0.2, 0.2, h, 0.06) +
               plateau(x, y, 0.25, -0.25, h, 0.04);
    };
    const Run r = run(test::make_grid(120, 1.0, height), 0.08);
    REQUIRE(r.texels.texels.size() == 3);
    check_invariants(r);
    // Each texel covers its bump's top and nothing of the flat ground: every face has a
    // raised vertex, and every face raised to the full height is in a texel.
    for (const Texel& t : r.texels.texels)
        for (int f : t.faces) {
            double z = 0;
            for (int v : r.mesh.faces[f]) z = std::max(z, r.mesh.positions[v].z());
            CHECK(z > 0);
        }
    for (int f = 0; f < r.mesh.num_faces(); ++f) {
        double z = h;
        for (int v : r.mesh.faces[f]) z = std::min(z, r.mesh.positions[v].z());
        if (z >= h) CHECK(r.texels.face_texel[f] >= 0);
    }
    CHECK(r.texels.global_threshold > 0);
    // Nothing is engraved: the negative orientation finds nothing on the bumps. (It may
    // find the trough that the disc mean leaves around each bump, paper eq. 1 being a
    // symmetric smoothing; see the issue notes.)
    const Run neg = run(test::make_grid(120, 1.0, height), 0.08, DetailOrientation::Negative);
    for (const Texel& t : neg.texels.texels)
        for (int f : t.faces) {
            double z = 0;
            for (int v : neg.mesh.faces[f]) z += neg.mesh.positions[v].z() / 3;
            CHECK(z < h / 2);  // not on a bump by the paper's ground-truth rule (§4.1)
        }
}

TEST_CASE("make_texels: a perfect sphere and a plane have no texel", "[geometry][texels]") {
    for (auto o : {DetailOrientation::Positive, DetailOrientation::Negative}) {
        CHECK(run(test::make_sphere(1.0, 5), 0.08, o).texels.texels.empty());
        CHECK(run(test::make_grid(40, 1.0), 0.08, o).texels.texels.empty());
    }
}

TEST_CASE("make_texels: same texels after rescaling by 10^k", "[geometry][texels]") {
    auto height = [](double x, double y) {
        return plateau(x, y, 0.1, 0.0, 0.02, 0.06) + plateau(x, y, -0.2, 0.1, 0.02, 0.05);
    };
    const Run ref = run(test::make_grid(80, 1.0, height), 0.08);
    REQUIRE(ref.texels.texels.size() == 2);
    for (double k : {1e-3, 1e3}) {
        const Run r = run(test::scaled(test::make_grid(80, 1.0, height), k), 0.08 * k);
        REQUIRE(r.texels.texels.size() == ref.texels.texels.size());
        for (std::size_t i = 0; i < r.texels.texels.size(); ++i)
            CHECK(r.texels.texels[i].faces == ref.texels.texels[i].faces);
    }
}

TEST_CASE("depth_interval_overlap: fraction of the narrower interval", "[geometry][texels]") {
    // ]0,2[ and ]1,3[: overlap 1, narrower width 2.
    CHECK(depth_interval_overlap(1, 1, 2, 1) == Approx(0.5));
    // ]0,4[ contains ]1,2[: the narrower is fully covered.
    CHECK(depth_interval_overlap(2, 2, 1.5, 0.5) == Approx(1.0));
    // Disjoint.
    CHECK(depth_interval_overlap(0, 1, 5, 1) == 0);
    // Symmetric.
    CHECK(depth_interval_overlap(2, 1, 1, 1) == depth_interval_overlap(1, 1, 2, 1));
    // Zero-width intervals: inside or not.
    CHECK(depth_interval_overlap(1, 0, 1, 0.5) == 1);
    CHECK(depth_interval_overlap(3, 0, 1, 0.5) == 0);
    CHECK(depth_interval_overlap(1, 0, 1, 0) == 1);
}

TEST_CASE("make_texels: merge threshold decides whether touching regions join",
          "[geometry][texels]") {
    // A long ridge: its two ends are local maxima one ridge-length apart, both grow the same
    // connected region, so the regions overlap fully and merge at any threshold <= 1.
    auto ridge = [](double x, double y) {
        const double qx = std::abs(x) - 0.2, qy = std::abs(y) - 0.025;
        const double d =
            std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0);
        return 0.02 * std::max(0.0, std::min(1.0, 0.5 - d / 0.01));
    };
    const Run r = run(test::make_grid(140, 1.0, ridge), 0.06);
    check_invariants(r);
    REQUIRE(r.texels.texels.size() == 1);
    CHECK(r.texels.num_regions >= 2);
    CHECK(r.texels.num_merges >= 1);

    // Two plateaus of different heights side by side: several seeds on each, whose regions
    // touch. Threshold 0 merges every touching pair, so no two texels share an edge;
    // threshold 1 only merges nested intervals, so touching texels remain.
    auto steps = [](double x, double y) {
        if (std::abs(y) > 0.08 || std::abs(x) > 0.25) return 0.0;
        return x < 0 ? 0.01 : 0.03;
    };
    auto touching_pairs = [](const Run& run) {
        int n = 0;
        for (int f = 0; f < run.mesh.num_faces(); ++f)
            for (int g : run.topology.face_neighbours_of(f))
                if (g > f && run.texels.face_texel[f] >= 0 && run.texels.face_texel[g] >= 0 &&
                    run.texels.face_texel[f] != run.texels.face_texel[g])
                    ++n;
        return n;
    };
    const Run strict =
        run(test::make_grid(160, 1.0, steps), 0.06, DetailOrientation::Positive, 1.0);
    const Run usual = run(test::make_grid(160, 1.0, steps), 0.06, DetailOrientation::Positive, 0.5);
    const Run loose = run(test::make_grid(160, 1.0, steps), 0.06, DetailOrientation::Positive, 0.0);
    for (const Run* r : {&strict, &usual, &loose}) check_invariants(*r);
    CHECK(loose.texels.num_regions > 2);
    CHECK(touching_pairs(loose) == 0);
    CHECK(touching_pairs(strict) > 0);
    CHECK(strict.texels.texels.size() > usual.texels.texels.size());
    CHECK(usual.texels.texels.size() == 2);  // one per plateau
    CHECK(strict.texels.num_merges < usual.texels.num_merges);
}

TEST_CASE("make_texels: preconditions", "[geometry][texels]") {
    const Mesh m = test::make_grid(4, 1.0);
    const MeshTopology t = make_topology(m);
    DepthMap d;
    d.vertex_depth.assign(m.num_vertices(), 0.0);
    d.face_depth.assign(m.num_faces(), 0.0);
    TexelParams p;
    p.radius = 0;
    REQUIRE_THROWS_AS(make_texels(m, t, d, p), InvalidInput);
    p.radius = 0.1;
    p.merge_overlap = 2;
    REQUIRE_THROWS_AS(make_texels(m, t, d, p), InvalidInput);
    p.merge_overlap = 0.5;
    d.face_depth.pop_back();
    REQUIRE_THROWS_AS(make_texels(m, t, d, p), InvalidInput);
}
