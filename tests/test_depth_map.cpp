#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "common/errors.hpp"
#include "geometry/depth_map.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

DepthMap depth_of(const Mesh& m, double radius, DetailOrientation o,
                  SmoothingMethod method = SmoothingMethod::Twicing) {
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    SmoothingParams p;
    p.radius = radius;
    p.method = method;
    return make_depth_map(m, mm.vertex_normal, make_smoothed_surface(m, t, mm, p), o);
}

// A plateau bump of height h and radius a on a plane, with a linear ramp of width w.
double plateau(double x, double y, double h, double a, double w) {
    const double d = std::hypot(x, y) - a;
    return h * std::max(0.0, std::min(1.0, 0.5 - d / w));
}

}  // namespace

TEST_CASE("make_depth_map: zero depth on a plane", "[geometry][depth]") {
    const Mesh m = test::make_grid(30, 1.0);
    for (auto method : {SmoothingMethod::Mean, SmoothingMethod::Twicing})
        for (auto o : {DetailOrientation::Positive, DetailOrientation::Negative}) {
            const DepthMap d = depth_of(m, 0.1, o, method);
            // Interior vertices: the disc mean lies on the plane. Border vertices average a
            // half disc, still on the plane. Only rounding remains.
            CHECK(d.max_depth < 1e-12);
        }
}

TEST_CASE("make_depth_map: a sphere has zero depth with twicing, r^2/4R with the paper's mean",
          "[geometry][depth]") {
    const double R = 1.0, r = 0.16;
    const Mesh m = test::make_sphere(R, 5);
    const DepthMap twicing = depth_of(m, r, DetailOrientation::Positive);
    // Twicing leaves r^4 / 16 R^3 = 4e-5 of shrinkage; the jagged border of the discrete
    // disc adds a vertex-to-vertex jitter (measured: mean 1e-4, max 3.3e-4 here, both
    // falling with finer meshes). The mean depth is 50 times below the paper's r^2 / 4R and
    // the largest stays under a quarter of the saliency floor 0.01 r, so a sphere never
    // yields a texel.
    double twicing_sum = 0;
    for (double x : twicing.vertex_depth) twicing_sum += x;
    CHECK(twicing_sum / m.num_vertices() < r * r / (4 * R) / 50);
    CHECK(twicing.max_depth < 0.25 * 0.01 * r);
    const DepthMap mean = depth_of(m, r, DetailOrientation::Positive, SmoothingMethod::Mean);
    // The cap of chord radius r has its centroid r^2 / 4R below the surface; the discrete
    // disc holds vertices up to r, so the mean depth is close to that (within 10%).
    double sum = 0;
    for (double x : mean.vertex_depth) sum += x;
    CHECK(sum / m.num_vertices() == Approx(r * r / (4 * R)).epsilon(0.1));
    // A convex surface stands out of its shrunk copy: nothing is negative.
    CHECK(depth_of(m, r, DetailOrientation::Negative, SmoothingMethod::Mean).max_depth < 1e-12);
}

TEST_CASE("make_depth_map: a bump has positive depth, none with the negative orientation",
          "[geometry][depth]") {
    const double h = 0.02, a = 0.05, w = 0.01;
    const Mesh m =
        test::make_grid(100, 1.0, [&](double x, double y) { return plateau(x, y, h, a, w); });
    const int center = 50 * 101 + 50;
    const DepthMap pos = depth_of(m, 0.1, DetailOrientation::Positive);
    CHECK(pos.vertex_depth[center] > 0.5 * h);
    CHECK(pos.vertex_depth[center] <= h * 1.01);
    CHECK(pos.max_depth == Approx(pos.vertex_depth[center]).epsilon(0.05));
    // Far from the bump the plane is untouched.
    CHECK(pos.vertex_depth[10 * 101 + 10] == 0);
    const DepthMap neg = depth_of(m, 0.1, DetailOrientation::Negative);
    CHECK(neg.vertex_depth[center] == 0);
    // A pit is the mirror image: found by the negative orientation only.
    const Mesh pit =
        test::make_grid(100, 1.0, [&](double x, double y) { return -plateau(x, y, h, a, w); });
    CHECK(depth_of(pit, 0.1, DetailOrientation::Negative).vertex_depth[center] > 0.5 * h);
    CHECK(depth_of(pit, 0.1, DetailOrientation::Positive).vertex_depth[center] == 0);
    // Face depth is the mean of the vertex depths.
    const auto& f = m.faces[1234];
    CHECK(pos.face_depth[1234] ==
          Approx((pos.vertex_depth[f[0]] + pos.vertex_depth[f[1]] + pos.vertex_depth[f[2]]) / 3));
}

TEST_CASE("make_depth_map: rescaling by 10^k scales the depth", "[geometry][depth]") {
    const Mesh m = test::make_grid(
        60, 1.0, [](double x, double y) { return plateau(x, y, 0.02, 0.08, 0.02); });
    // A radius that is no multiple of the grid spacing: no vertex sits on the sphere, where
    // rounding of a rescaled distance could flip its membership.
    const double r = 0.1537;
    const DepthMap ref = depth_of(m, r, DetailOrientation::Positive);
    for (double k : {1e-3, 1e3}) {
        const DepthMap d = depth_of(test::scaled(m, k), r * k, DetailOrientation::Positive);
        CHECK(d.max_depth == Approx(ref.max_depth * k).epsilon(1e-9));
        for (int v = 0; v < m.num_vertices(); v += 7)
            CHECK(d.vertex_depth[v] ==
                  Approx(ref.vertex_depth[v] * k).epsilon(1e-9).margin(1e-12 * k));
    }
}

TEST_CASE("make_depth_map: an open border on a curved surface has no depth", "[geometry][depth]") {
    // A hemisphere of radius 1 cut at the equator: discs at the border are one-sided. Their
    // mean drifts about 0.4 r into the interior; were the smoothed point moved there, the
    // border would stand about that far out of the smoothed surface. Along the normal only,
    // the border keeps the interior's tiny twicing error (well below the 0.01 r floor of
    // the texel stage), and the depth beyond the reach of twicing (2 r, plus a margin) is
    // unchanged.
    const Mesh sphere = test::make_sphere(1.0, 5);
    Mesh half;
    half.positions = sphere.positions;
    for (const auto& f : sphere.faces)
        if (sphere.positions[f[0]].z() + sphere.positions[f[1]].z() + sphere.positions[f[2]].z() >
            0)
            half.faces.push_back(f);
    const double r = 0.15;
    const DepthMap d = depth_of(half, r, DetailOrientation::Positive);
    CHECK(d.max_depth < 0.01 * r);
    const DepthMap full = depth_of(sphere, r, DetailOrientation::Positive);
    for (int v = 0; v < sphere.num_vertices(); ++v)
        if (sphere.positions[v].z() > 3 * r)
            CHECK(d.vertex_depth[v] == Approx(full.vertex_depth[v]).margin(1e-12));
}

TEST_CASE("make_smoothed_surface: rejects a bad radius and mismatched inputs",
          "[geometry][depth]") {
    const Mesh m = test::make_grid(4, 1.0);
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    SmoothingParams p;
    p.radius = 0;
    REQUIRE_THROWS_AS(make_smoothed_surface(m, t, mm, p), InvalidInput);
    p.radius = std::nan("");
    REQUIRE_THROWS_AS(make_smoothed_surface(m, t, mm, p), InvalidInput);
    p.radius = 0.1;
    REQUIRE_THROWS_AS(make_smoothed_surface(m, t, {}, p), InvalidInput);
    MeshMetrics no_normal = mm;
    no_normal.vertex_normal.pop_back();
    REQUIRE_THROWS_AS(make_smoothed_surface(m, t, no_normal, p), InvalidInput);
    SmoothedSurface s = make_smoothed_surface(m, t, mm, p);
    s.positions.pop_back();
    REQUIRE_THROWS_AS(make_depth_map(m, mm.vertex_normal, s, DetailOrientation::Positive),
                      InvalidInput);
}

TEST_CASE(
    "SurfaceSmoother: no exclusion gives make_smoothed_surface's bits; excluded vertices stay",
    "[geometry][depth]") {
    // A plateau bump on a plane: leaving the bump out of the discs puts the smoothed surface
    // of the plane back on the plane (it is flat), where the bump pulled it up before.
    const double h = 0.1, a = 0.3, w = 0.05, r = 0.4;
    Mesh m = test::make_grid(60, 3.0);
    for (auto& p : m.positions) p.z() = plateau(p.x(), p.y(), h, a, w);
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    SmoothingParams p;
    p.radius = r;
    const SurfaceSmoother smoother(m, t, mm, p);
    const SmoothedSurface plain = smoother.smooth();
    CHECK(plain.positions == make_smoothed_surface(m, t, mm, p).positions);
    CHECK(smoother.smooth(std::vector<char>(m.num_vertices(), 0)).positions == plain.positions);

    std::vector<char> bump(m.num_vertices(), 0);
    for (int v = 0; v < m.num_vertices(); ++v) bump[v] = m.positions[v].z() > 0 ? 1 : 0;
    const SmoothedSurface without = smoother.smooth(bump);
    double pulled = 0, left = 0;
    for (int v = 0; v < m.num_vertices(); ++v) {
        if (bump[v]) {
            CHECK(without.positions[v] == m.positions[v]);
            continue;
        }
        pulled = std::max(pulled, plain.positions[v].z());
        left = std::max(left, std::abs(without.positions[v].z()));
    }
    CHECK(pulled > 0.05 * h);  // the bump raises the plane's smoothed surface around it...
    CHECK(left < 1e-12);       // ...and, left out, not at all (the plane is exactly flat)
    REQUIRE_THROWS_AS(smoother.smooth(std::vector<char>(3, 0)), InvalidInput);
}

namespace {

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5), written
// apart from the library's (CGAL's) so that the test checks it independently.
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denom = 1 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

TEST_CASE("make_depth_map: the distance to the nearest triangle of the whole oriented surface",
          "[geometry][depth]") {
    // 81,920 faces: enough for the search to split the surface in two halves.
    Mesh m = test::make_sphere(1.0, 6);
    const Eigen::Vector3d bumps[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}, {0.6, 0.6, 0.52}};
    for (auto& p : m.positions) {
        double lift = 0;
        for (const auto& b : bumps)
            lift += 0.05 * std::exp(-(p - b.normalized()).squaredNorm() / 0.01);
        p *= 1 + lift;
    }
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    SmoothingParams sp;
    sp.radius = 0.3;
    const SmoothedSurface s = make_smoothed_surface(m, t, mm, sp);
    for (DetailOrientation o : {DetailOrientation::Positive, DetailOrientation::Negative}) {
        const DepthMap d = make_depth_map(m, mm.vertex_normal, s, o);
        const double sign = o == DetailOrientation::Positive ? 1 : -1;
        std::vector<Eigen::Vector3d> oriented(m.num_vertices());
        for (int v = 0; v < m.num_vertices(); ++v)
            oriented[v] = sign * (m.positions[v] - s.positions[v]).dot(mm.vertex_normal[v]) > 0
                              ? s.positions[v]
                              : m.positions[v];
        int checked = 0;
        for (int v = 0; v < m.num_vertices(); v += 61) {
            if (oriented[v] == m.positions[v]) {
                CHECK(d.vertex_depth[v] == 0);
                continue;
            }
            double best = std::numeric_limits<double>::infinity();
            for (const auto& f : m.faces)
                best = std::min(best, (closest_on_triangle(m.positions[v], oriented[f[0]],
                                                           oriented[f[1]], oriented[f[2]]) -
                                       m.positions[v])
                                          .norm());
            CHECK(d.vertex_depth[v] == Approx(best).margin(1e-12));
            ++checked;
        }
        CHECK(checked > 40);
    }
}

TEST_CASE(
    "DepthMapper: one mapper for several surfaces gives each its own distances, within each "
    "component",
    "[geometry][depth]") {
    // Two bumpy grids one above the other, 0.01 apart: a vertex of one must never measure its
    // depth to the other.
    const Mesh a =
        test::make_grid(24, 1.0, [](double x, double y) { return plateau(x, y, 0.05, 0.1, 0.05); });
    Mesh b = a;
    for (auto& p : b.positions) p.z() += 0.01;
    const Mesh m = test::combined(a, b);
    const MeshTopology t = make_topology(m);
    const MeshMetrics mm = make_mesh_metrics(m, t);
    const VertexComponents parts = vertex_components(m);
    REQUIRE(parts.num_components == 2);
    const DepthMapper mapper(m);
    for (double r : {0.15, 0.3}) {
        SmoothingParams sp;
        sp.radius = r;
        const SmoothedSurface s = make_smoothed_surface(m, t, mm, sp);
        for (auto o : {DetailOrientation::Positive, DetailOrientation::Negative}) {
            const DepthMap d = mapper.map(mm.vertex_normal, s, o);
            // The oriented surface, and each vertex's distance to its own component's part of
            // it by a search over every proper triangle.
            const double sign = o == DetailOrientation::Positive ? 1 : -1;
            std::vector<Eigen::Vector3d> oriented = m.positions;
            for (int v = 0; v < m.num_vertices(); ++v)
                if (sign * (m.positions[v] - s.positions[v]).dot(mm.vertex_normal[v]) > 0)
                    oriented[v] = s.positions[v];
            int moved = 0;
            for (int v = 0; v < m.num_vertices(); ++v) {
                if (oriented[v] == m.positions[v]) {
                    CHECK(d.vertex_depth[v] == 0);
                    continue;
                }
                ++moved;
                double best = std::numeric_limits<double>::infinity();
                for (const auto& f : m.faces) {
                    if (parts.component[f[0]] != parts.component[v]) continue;
                    const Eigen::Vector3d &p0 = oriented[f[0]], &p1 = oriented[f[1]],
                                          &p2 = oriented[f[2]];
                    if ((p1 - p0).cross(p2 - p0).squaredNorm() == 0) continue;
                    const double d2 = test::triangle_squared_distance(m.positions[v], p0, p1, p2);
                    best = std::min(best, d2);
                }
                REQUIRE(d.vertex_depth[v] == Approx(std::sqrt(best)).margin(1e-12));
            }
            CHECK(moved == d.num_moved_vertices);
            CHECK(moved > 0);
        }
    }
}
