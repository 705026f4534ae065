#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>

#include "common/errors.hpp"
#include "geometry/curvature.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {
CurvatureField curvature_of(const Mesh& m) {
    const MeshTopology t = make_topology(m);
    return make_curvature(m, t, make_mesh_metrics(m, t).vertex_normal);
}
}  // namespace

TEST_CASE("make_curvature: spheres of two radii", "[geometry][curvature]") {
    // On an icosphere of level 4 the discrete operators are within about 1% of the smooth
    // values (the triangles are nearly equilateral); 3% leaves room for the 12 valence-5
    // vertices.
    for (double radius : {1.0, 3.0}) {
        const Mesh m = test::make_sphere(radius, 4);
        const CurvatureField c = curvature_of(m);
        for (int v = 0; v < m.num_vertices(); ++v) {
            CHECK(c.gaussian[v] == Approx(1 / (radius * radius)).epsilon(0.03));
            CHECK(c.mean[v] == Approx(1 / radius).epsilon(0.03));
            CHECK(c.shape_index[v] > 0.9);  // umbilic: +1 up to the noise of k1 - k2
            CHECK(c.curvedness[v] == Approx(1 / radius).epsilon(0.03));
        }
    }
}

TEST_CASE("make_curvature: sphere with inward faces is concave", "[geometry][curvature]") {
    Mesh m = test::make_sphere(2.0, 3);
    for (auto& f : m.faces) std::swap(f[1], f[2]);
    const CurvatureField c = curvature_of(m);
    for (int v = 0; v < m.num_vertices(); ++v) {
        CHECK(c.mean[v] == Approx(-0.5).epsilon(0.03));
        CHECK(c.shape_index[v] < -0.9);  // cup
    }
}

TEST_CASE("make_curvature: cylinder is a ridge with zero Gaussian curvature",
          "[geometry][curvature]") {
    const double radius = 2.0;
    const Mesh m = test::make_cylinder(radius, 6.0, 48, 40);
    const CurvatureField c = curvature_of(m);
    const MeshTopology t = make_topology(m);
    int interior = 0;
    for (int v = 0; v < m.num_vertices(); ++v) {
        if (t.vertex_on_boundary[v]) {
            CHECK(std::isnan(c.gaussian[v]));  // border vertices have no defined curvature
            continue;
        }
        ++interior;
        // The angle defect of this symmetric triangulation vanishes up to rounding.
        CHECK(std::abs(c.gaussian[v]) < 1e-9);
        CHECK(c.mean[v] == Approx(1 / (2 * radius)).epsilon(0.01));
        CHECK(c.shape_index[v] == Approx(0.5).margin(0.01));
    }
    CHECK(interior > 1000);
}

TEST_CASE("make_curvature: rescaling by 10^k scales curvatures, keeps the shape index",
          "[geometry][curvature]") {
    const Mesh m = test::make_sphere(1.0, 3);
    const CurvatureField ref = curvature_of(m);
    for (double k : {1e-3, 1e3}) {
        const CurvatureField c = curvature_of(test::scaled(m, k));
        for (int v = 0; v < m.num_vertices(); v += 17) {
            CHECK(c.gaussian[v] == Approx(ref.gaussian[v] / (k * k)).epsilon(1e-9));
            CHECK(c.mean[v] == Approx(ref.mean[v] / k).epsilon(1e-9));
            CHECK(c.shape_index[v] == Approx(ref.shape_index[v]).margin(1e-9));
        }
    }
}

TEST_CASE("make_curvature: plane is flat; normals must match the mesh", "[geometry][curvature]") {
    const Mesh m = test::make_grid(10, 1.0);
    const CurvatureField c = curvature_of(m);
    const MeshTopology t = make_topology(m);
    for (int v = 0; v < m.num_vertices(); ++v)
        if (!t.vertex_on_boundary[v]) {
            CHECK(std::abs(c.gaussian[v]) < 1e-9);
            CHECK(std::abs(c.mean[v]) < 1e-9);
            CHECK(std::isnan(c.shape_index[v]));  // undefined where the curvedness is ~0
        }
    REQUIRE_THROWS_AS(make_curvature(m, t, {}), InvalidInput);
}

// ---- the quadric fit over a geodesic disc (CurvatureParams::radius) ------------------------

namespace {
CurvatureField fitted_curvature_of(const Mesh& m, double radius) {
    const MeshTopology t = make_topology(m);
    CurvatureParams p;
    p.radius = radius;
    return make_curvature(m, t, make_mesh_metrics(m, t).vertex_normal, p);
}

// Moves every vertex along its radius by a uniform draw in [-amplitude, amplitude]
// (deterministic: a fixed linear congruential sequence).
Mesh radially_perturbed(Mesh m, double amplitude) {
    std::uint64_t state = 12345;
    for (auto& p : m.positions) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const double u = static_cast<double>(state >> 11) / 9007199254740992.0;  // [0, 1)
        p *= 1 + amplitude * (2 * u - 1) / p.norm();
    }
    return m;
}

double rms_relative_error(const std::vector<double>& values, double expected) {
    double sum = 0;
    int n = 0;
    for (double v : values)
        if (!std::isnan(v)) {
            sum += (v / expected - 1) * (v / expected - 1);
            ++n;
        }
    return n > 0 ? std::sqrt(sum / n) : 1e9;
}
}  // namespace

TEST_CASE("make_curvature: a fitted quadric gives a sphere's curvature", "[geometry][curvature]") {
    // A quadric through points of a sphere of radius R over a disc of radius rho differs from
    // it by O(rho^2 / R^2): 1/R to within 1% at rho = R / 10.
    for (double radius : {1.0, 3.0}) {
        const Mesh m = test::make_sphere(radius, 5);
        const CurvatureField c = fitted_curvature_of(m, radius / 10);
        for (int v = 0; v < m.num_vertices(); v += 7) {
            CHECK(c.gaussian[v] == Approx(1 / (radius * radius)).epsilon(0.01));
            CHECK(c.mean[v] == Approx(1 / radius).epsilon(0.01));
            CHECK(c.shape_index[v] > 0.95);
        }
    }
}

TEST_CASE("make_curvature: a fitted quadric gives a cylinder's ridge", "[geometry][curvature]") {
    const double radius = 2.0;
    const Mesh m = test::make_cylinder(radius, 6.0, 96, 80);
    const MeshTopology t = make_topology(m);
    const CurvatureField c = fitted_curvature_of(m, 0.4);
    int checked = 0;
    for (int v = 0; v < m.num_vertices(); ++v) {
        if (t.vertex_on_boundary[v]) continue;
        // Vertices whose disc reaches the open ends see a one-sided disc: still a cylinder.
        CHECK(std::abs(c.gaussian[v]) < 1e-3);
        CHECK(c.mean[v] == Approx(1 / (2 * radius)).epsilon(0.01));
        CHECK(c.shape_index[v] == Approx(0.5).margin(0.01));
        ++checked;
    }
    CHECK(checked > 4000);
}

TEST_CASE("make_curvature: the fit averages out sampling noise the one-ring amplifies",
          "[geometry][curvature]") {
    // Radial noise of 0.3% of the radius on a level-6 icosphere (edges of about 1.9% of the
    // radius, so a disc of radius R / 10 is about five edges across, as 0.6 r is on sphere-1
    // at r = 4%): the one-ring's mean curvature errs by about e / l^2, ten times the
    // curvature itself. Measured RMS relative errors: one-ring 10.4, fit 0.20 (mean
    // curvature) and 0.40 (Gaussian).
    const double radius = 1.0;
    const Mesh m = radially_perturbed(test::make_sphere(radius, 6), 0.003 * radius);
    const CurvatureField ring = curvature_of(m);
    const CurvatureField fit = fitted_curvature_of(m, radius / 10);
    const double ring_error = rms_relative_error(ring.mean, 1 / radius);
    const double fit_error = rms_relative_error(fit.mean, 1 / radius);
    INFO("one-ring RMS relative error " << ring_error << ", fit " << fit_error);
    CHECK(ring_error > 5);
    CHECK(fit_error < 0.3);
    CHECK(fit_error < ring_error / 20);
    CHECK(rms_relative_error(fit.gaussian, 1 / (radius * radius)) < 0.6);
}

TEST_CASE("make_curvature: too small a disc falls back to the one-ring; bad radius throws",
          "[geometry][curvature]") {
    const Mesh m = test::make_sphere(1.0, 3);
    const CurvatureField ring = curvature_of(m);
    // A radius below the edge length holds only the vertex itself: the one-ring result.
    const CurvatureField tiny = fitted_curvature_of(m, 1e-6);
    for (int v = 0; v < m.num_vertices(); ++v) CHECK(tiny.mean[v] == ring.mean[v]);
    const MeshTopology t = make_topology(m);
    const auto normals = make_mesh_metrics(m, t).vertex_normal;
    for (double bad : {-1.0, std::nan(""), HUGE_VAL}) {
        CurvatureParams p;
        p.radius = bad;
        CHECK_THROWS_AS(make_curvature(m, t, normals, p), InvalidInput);
    }
}

TEST_CASE("make_curvature: a vertex mask computes only the flagged vertices",
          "[geometry][curvature]") {
    const Mesh m = test::make_sphere(1.0, 4);
    const MeshTopology t = make_topology(m);
    const auto normals = make_mesh_metrics(m, t).vertex_normal;
    CurvatureParams p;
    p.radius = 0.2;
    const CurvatureField all = make_curvature(m, t, normals, p);
    p.only.assign(static_cast<std::size_t>(m.num_vertices()), 0);
    for (int v = 0; v < m.num_vertices(); v += 3) p.only[v] = 1;
    const CurvatureField some = make_curvature(m, t, normals, p);
    for (int v = 0; v < m.num_vertices(); ++v) {
        if (v % 3 == 0) {
            CHECK(some.mean[v] == all.mean[v]);
            CHECK(some.gaussian[v] == all.gaussian[v]);
        } else {
            CHECK(std::isnan(some.mean[v]));
            CHECK(std::isnan(some.shape_index[v]));
        }
    }
    p.only.pop_back();
    CHECK_THROWS_AS(make_curvature(m, t, normals, p), InvalidInput);
}
