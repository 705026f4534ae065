#include <catch2/catch.hpp>

#include <cmath>

#include "geometry/curvature.hpp"
#include "geometry/errors.hpp"
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

TEST_CASE("make_curvature: cylinder is a ridge with zero Gaussian curvature", "[geometry][curvature]") {
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

TEST_CASE("make_curvature: rescaling by 10^k scales curvatures, keeps the shape index", "[geometry][curvature]") {
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
