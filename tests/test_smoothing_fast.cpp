// The fast disc means (DiscMode::Fast) against the exact ones, which stay the reference.

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "common/errors.hpp"
#include "geometry/depth_map.hpp"
#include "geometry/disc_means.hpp"
#include "geometry/evaluation.hpp"
#include "geometry/neighbourhood.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/synth.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

SmoothedSurface smoothed(const Mesh& m, double radius, DiscMode disc,
                         SmoothingMethod method = SmoothingMethod::Twicing) {
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    SmoothingParams p;
    p.radius = radius;
    p.method = method;
    p.disc = disc;
    return make_smoothed_surface(m, t, mm, p);
}

// How the fast run deviates from the exact run on a synthetic sphere.
struct Deviation {
    double max_depth_error = 0;   // largest |depth_fast - depth_exact| / displacement height
    double mean_depth_error = 0;  // mean of the same over all vertices
    int num_exact_texels = 0;
    int num_fast_texels = 0;
    int num_matched = 0;           // exact texels whose best fast match has IoU >= 0.9
    double min_iou = 1;            // over the exact texels
    double face_disagreement = 0;  // fraction of faces in a texel in one run and not the other
    int num_interpolated = 0;
};

Deviation compare_on_sphere(int level, double scale) {
    SynthParams sp;
    sp.level = level;
    const SyntheticMesh synth = make_synthetic_sphere(sp);
    SegmentationParams p;
    p.radius_rel = scale;
    p.disc = DiscMode::Exact;
    const Segmentation exact = run_segmentation(synth.mesh, p);
    p.disc = DiscMode::Fast;
    const Segmentation fast = run_segmentation(synth.mesh, p);
    Deviation d;
    d.num_interpolated = fast.num_interpolated_vertices;
    const double height = sp.displacement_rel;  // the sphere has radius 1
    const auto& de = exact.positive_depth->vertex_depth;
    const auto& df = fast.positive_depth->vertex_depth;
    double sum = 0;
    for (std::size_t v = 0; v < de.size(); ++v) {
        const double e = std::abs(de[v] - df[v]) / height;
        d.max_depth_error = std::max(d.max_depth_error, e);
        sum += e;
    }
    d.mean_depth_error = sum / static_cast<double>(de.size());
    d.num_exact_texels = static_cast<int>(exact.texels.size());
    d.num_fast_texels = static_cast<int>(fast.texels.size());
    int differ = 0;
    for (std::size_t f = 0; f < exact.face_texel.size(); ++f)
        if ((exact.face_texel[f] >= 0) != (fast.face_texel[f] >= 0)) ++differ;
    d.face_disagreement =
        static_cast<double>(differ) / static_cast<double>(exact.face_texel.size());
    for (const Texel& t : exact.texels) {
        std::map<int, int> overlap;  // fast texel -> shared faces
        for (int f : t.faces)
            if (fast.face_texel[f] >= 0) ++overlap[fast.face_texel[f]];
        double best = 0;
        for (const auto& [id, shared] : overlap) {
            const double uni =
                static_cast<double>(t.faces.size() + fast.texels[id].faces.size() - shared);
            best = std::max(best, shared / uni);
        }
        d.min_iou = std::min(d.min_iou, best);
        if (best >= 0.9) ++d.num_matched;
    }
    return d;
}

void print(const char* what, const Deviation& d) {
    std::printf(
        "%s: depth error max %.4f mean %.5f of the displacement; texels exact %d fast %d, matched "
        "%d, "
        "min IoU %.3f, faces differing %.5f; %d vertices interpolated\n",
        what, d.max_depth_error, d.mean_depth_error, d.num_exact_texels, d.num_fast_texels,
        d.num_matched, d.min_iou, d.face_disagreement, d.num_interpolated);
}

}  // namespace

TEST_CASE("make_smoothed_surface: fast disc means give the exact texels of sphere-1",
          "[geometry][smoothing][slow]") {
    // Level 6 (81,920 faces) at scale 0.08: discs of about 260 vertices, as at level 7 and
    // the paper's 0.04. Measured: depth error max 0.081, mean 0.0033 of the displacement
    // height; 88 texels each, every exact texel matched with IoU >= 0.9 (min 0.929), faces
    // in a texel in one run only 0.054%. Without the tangential correction, texel matching
    // and the largest depth error fail. The bounds leave about a factor 2.
    const Deviation d = compare_on_sphere(6, 0.08);
    INFO("depth error max " << d.max_depth_error << " mean " << d.mean_depth_error << " texels "
                            << d.num_exact_texels << " / " << d.num_fast_texels << " matched "
                            << d.num_matched << " min IoU " << d.min_iou << " faces differing "
                            << d.face_disagreement);
    CHECK(d.num_interpolated > 0);
    CHECK(d.num_fast_texels == d.num_exact_texels);
    CHECK(d.num_matched == d.num_exact_texels);
    CHECK(d.max_depth_error < 0.15);
    CHECK(d.mean_depth_error < 0.007);
    CHECK(d.face_disagreement < 0.002);
}

TEST_CASE("make_smoothed_surface: fast deviation on sphere-1 level 7 (measurement)",
          "[.][measure]") {
    for (double scale : {0.04, 0.08}) {
        const Deviation d = compare_on_sphere(7, scale);
        char what[64];
        std::snprintf(what, sizeof what, "sphere-1 level 7, scale %.2f", scale);
        print(what, d);
    }
}

TEST_CASE(
    "make_smoothed_surface: fast twicing keeps an icosphere within a small bound of the exact",
    "[geometry][smoothing]") {
    // Level 5 (10,242 vertices) with r = 0.3: discs of about 230 vertices; s = 0.075, h = 0.15.
    const double R = 1.0, r = 0.3;
    const Mesh m = test::make_sphere(R, 5);
    for (auto method : {SmoothingMethod::Twicing, SmoothingMethod::Mean}) {
        const SmoothedSurface exact = smoothed(m, r, DiscMode::Exact, method);
        const SmoothedSurface fast = smoothed(m, r, DiscMode::Fast, method);
        CHECK(exact.num_interpolated_vertices == 0);
        CHECK(fast.num_interpolated_vertices == m.num_vertices());
        CHECK(fast.num_samples < m.num_vertices() / 3);
        double worst = 0;
        for (int v = 0; v < m.num_vertices(); ++v)
            worst = std::max(worst, (exact.positions[v] - fast.positions[v]).norm());
        // The exact means jitter from vertex to vertex with the jagged border of the discrete
        // discs; the interpolation smooths that jitter away, so the two differ by about the
        // jitter (measured: worst 6.8e-4 twicing, 1.0e-3 mean, exact spread 1.1e-3). What
        // must agree is the radius of the smoothed sphere: measured mean radius difference
        // 8.3e-5 (twicing) and 4.4e-4 (mean: 2% of its shrinkage r^2/4R = 0.0225, the soft
        // edge of the patch quadrature); without the curvature term the mean's would be
        // about h^2/8R = 2.8e-3.
        auto radii = [&](const SmoothedSurface& s) {
            double lo = 2 * R, hi = 0, sum = 0;
            for (const auto& x : s.positions) {
                lo = std::min(lo, x.norm());
                hi = std::max(hi, x.norm());
                sum += x.norm();
            }
            return std::array<double, 3>{lo, hi, sum / static_cast<double>(s.positions.size())};
        };
        const auto e = radii(exact), f = radii(fast);
        INFO("method " << static_cast<int>(method) << " worst " << worst << " exact radii " << e[0]
                       << " " << e[1] << " " << e[2] << " fast " << f[0] << " " << f[1] << " "
                       << f[2]);
        CHECK(std::abs(f[2] - e[2]) < (method == SmoothingMethod::Twicing ? 2e-4 : 1e-3));
        CHECK(f[0] >= e[0] - 1e-4);
        CHECK(f[1] <= e[1] + 1e-4);
        CHECK(worst < e[1] - e[0]);
    }
}

TEST_CASE("DiscAverager: the interpolation is exact on a flat grid (linear precision)",
          "[geometry][smoothing]") {
    // A tilted 100 x 100 grid of side 1 and r = 0.1437 (no lattice point near the sphere, where
    // rounding would make a disc lopsided): discs of about 650 vertices. Away from the border
    // (r + h + sqrt(3) s) every disc is symmetric, its mean is the vertex itself, and each
    // sample's estimate M(c) + (v - c) is exactly v: only rounding is left. The samples'
    // discs are walked exactly here, to test the interpolation alone (the patch sums are
    // a quadrature of the disc, off by about 1e-3 r tangentially on this grid). Without the
    // tangential correction the error would be about s / 2.
    const Mesh m = test::make_grid(100, 1.0, [](double x, double y) { return 0.3 * x - 0.2 * y; });
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    DiscMeanParams p;
    p.radius = 0.1437;
    p.mode = DiscMode::Exact;
    const std::vector<Eigen::Vector3d> exact =
        DiscAverager(m, t, mm.vertex_area, mm.vertex_normal, p).means(m.positions);
    p.mode = DiscMode::Fast;
    p.exact_samples = true;
    const DiscAverager fast_averager(m, t, mm.vertex_area, mm.vertex_normal, p);
    const std::vector<Eigen::Vector3d> fast = fast_averager.means(m.positions);
    CHECK(fast_averager.num_interpolated_vertices() == m.num_vertices());
    const double margin = p.radius * (1 + p.sample_spacing_rel * (p.support_rel + std::sqrt(3.0)));
    int num_checked = 0;
    double worst = 0;
    for (int v = 0; v < m.num_vertices(); ++v) {
        const Eigen::Vector3d& x = m.positions[v];
        if (std::max(std::abs(x.x()), std::abs(x.y())) > 0.5 - margin) continue;
        ++num_checked;
        worst = std::max(worst, (fast[v] - exact[v]).norm());
    }
    INFO("checked " << num_checked << " worst " << worst);
    CHECK(num_checked > 0);
    CHECK(worst < 1e-12);
}

TEST_CASE("make_smoothed_surface: fast mode gives the same bits on 1 and all threads",
          "[geometry][smoothing]") {
    SynthParams sp;
    sp.level = 5;
    sp.noise_percent = 0.1;
    const SyntheticMesh synth = make_synthetic_sphere(sp);
    SmoothedSurface one, all;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = smoothed(synth.mesh, 0.3, DiscMode::Fast);
    }
    all = smoothed(synth.mesh, 0.3, DiscMode::Fast);
    CHECK(one.num_interpolated_vertices > 0);
    CHECK(one.num_samples == all.num_samples);
    CHECK(one.positions == all.positions);
}

TEST_CASE("make_smoothed_surface: Auto walks small discs exactly and samples large ones",
          "[geometry][smoothing]") {
    const Mesh m = test::make_sphere(1.0, 5);  // 10,242 vertices, about 0.0012 area each
    // r = 0.3: about 230 vertices per disc, under the threshold of 400: exact, same bits.
    const SmoothedSurface small_auto = smoothed(m, 0.3, DiscMode::Auto);
    CHECK(small_auto.num_interpolated_vertices == 0);
    CHECK(small_auto.num_samples == 0);
    CHECK(small_auto.positions == smoothed(m, 0.3, DiscMode::Exact).positions);
    // r = 0.45: about 520 vertices per disc: fast.
    const SmoothedSurface large_auto = smoothed(m, 0.45, DiscMode::Auto);
    CHECK(large_auto.num_interpolated_vertices == m.num_vertices());
    CHECK(large_auto.positions == smoothed(m, 0.45, DiscMode::Fast).positions);
    // A small component (a level-2 sphere, 162 vertices, discs of about 8) beside the large
    // one stays exact.
    const Mesh both = test::combined(m, test::make_sphere(1.0, 2, Eigen::Vector3d(5, 0, 0)));
    const SmoothedSurface mixed = smoothed(both, 0.45, DiscMode::Auto);
    CHECK(mixed.num_interpolated_vertices == m.num_vertices());
}

TEST_CASE("DiscAverager: preconditions", "[geometry][smoothing]") {
    const Mesh m = test::make_grid(4, 1.0);
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    DiscMeanParams p;
    REQUIRE_THROWS_AS(DiscAverager(m, t, mm.vertex_area, mm.vertex_normal, p),
                      InvalidInput);  // radius 0
    p.radius = 0.5;
    REQUIRE_THROWS_AS(DiscAverager(m, t, {}, mm.vertex_normal, p), InvalidInput);
    REQUIRE_THROWS_AS(DiscAverager(m, t, mm.vertex_area, {}, p), InvalidInput);
    p.sample_spacing_rel = 0;
    REQUIRE_THROWS_AS(DiscAverager(m, t, mm.vertex_area, mm.vertex_normal, p), InvalidInput);
    p.sample_spacing_rel = 0.25;
    p.support_rel = 1;
    REQUIRE_THROWS_AS(DiscAverager(m, t, mm.vertex_area, mm.vertex_normal, p), InvalidInput);
    p.support_rel = 2;
    const DiscAverager a(m, t, mm.vertex_area, mm.vertex_normal, p);
    REQUIRE_THROWS_AS(a.means({}), InvalidInput);
}

TEST_CASE("DiscAverager: exact means have the same bits whether discs are recorded or walked",
          "[geometry][smoothing]") {
    const Mesh m = test::make_sphere(1.0, 4);  // 2,562 vertices: many clusters of discs
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    // The reference: every disc walked over the mesh and summed in walking order (the
    // averager sums the same vertices in its clusters' order: equal to rounding).
    const double r = 0.3;
    std::vector<Eigen::Vector3d> reference(m.num_vertices());
    DiscWalker walker(m, t);
    for (int v = 0; v < m.num_vertices(); ++v) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        double total = 0;
        for (int u : walker.disc(v, r)) {
            sum += mm.vertex_area[u] * m.positions[u];
            total += mm.vertex_area[u];
        }
        reference[v] = sum / total;
    }
    DiscMeanParams p;
    p.radius = r;
    p.mode = DiscMode::Exact;
    std::vector<Eigen::Vector3d> first;
    for (std::size_t budget : {std::size_t{0}, std::size_t{5000}, p.max_recorded_disc_vertices}) {
        p.max_recorded_disc_vertices = budget;
        const DiscAverager a(m, t, mm.vertex_area, mm.vertex_normal, p);
        INFO("budget " << budget);
        const std::vector<Eigen::Vector3d> means = a.means(m.positions);
        if (first.empty()) first = means;
        CHECK(means == first);
        CHECK(a.means(m.positions) == first);  // a second pass reads the same records
        double worst = 0;
        for (int v = 0; v < m.num_vertices(); ++v)
            worst = std::max(worst, (means[v] - reference[v]).norm());
        CHECK(worst < 1e-14);
    }
}

TEST_CASE("make_disc_sampling: components given by the caller give the same sampling",
          "[geometry][disc_means]") {
    // Two pieces: a fine sphere whose discs of r = 0.5 hold about 10,000 * 0.25 pi / 4 pi
    // ~ 600 vertices (sampled), and a coarse one of radius 0.6 whose 42 vertices are fewer
    // than Auto's 400 (exact), so that the flags depend on the components.
    const Mesh fine = test::make_sphere(1.0, 5);
    const Mesh coarse = test::make_sphere(0.6, 1, Eigen::Vector3d(5, 0, 0));
    const Mesh m = test::combined(fine, coarse);
    DiscMeanParams p;
    p.radius = 0.5;
    const VertexComponents components = vertex_components(m);
    REQUIRE(components.num_components == 2);
    const DiscSampling own = make_disc_sampling(m, p);
    const DiscSampling given = make_disc_sampling(m, p, &components);
    CHECK(given.fast == own.fast);
    CHECK(given.origin == own.origin);
    CHECK(given.grid == own.grid);
    const auto nf = static_cast<std::size_t>(fine.num_vertices());
    CHECK(std::all_of(own.fast.begin(), own.fast.begin() + nf, [](char f) { return f == 1; }));
    CHECK(std::all_of(own.fast.begin() + nf, own.fast.end(), [](char f) { return f == 0; }));
    VertexComponents wrong = components;
    wrong.component.pop_back();
    CHECK_THROWS_AS(make_disc_sampling(m, p, &wrong), InvalidInput);
}
