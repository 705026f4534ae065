#include <catch2/catch.hpp>
#include <set>

#include "common/errors.hpp"
#include "geometry/synth.hpp"

using namespace geotex;

TEST_CASE("make_synthetic_sphere: sphere-1 layout and ground truth", "[geometry][synth]") {
    SynthParams p;
    p.level = 5;
    const SyntheticMesh s = make_synthetic_sphere(p);
    CHECK(s.mesh.num_faces() == 20480);
    REQUIRE(s.shapes.size() == 88);
    int count[4] = {0, 0, 0, 0};
    for (const auto& shape : s.shapes) ++count[static_cast<int>(shape.kind)];
    CHECK(count[0] == 17);
    CHECK(count[1] == 37);
    CHECK(count[2] == 16);
    CHECK(count[3] == 18);
    // Displacement within [0, 2%] of the radius, and reached on every shape.
    for (const auto& q : s.mesh.positions) {
        CHECK(q.norm() >= 1.0 - 1e-12);
        CHECK(q.norm() <= 1.02 + 1e-12);
    }
    std::vector<int> faces_of_shape(s.shapes.size(), 0);
    for (int f : s.face_shape)
        if (f >= 0) ++faces_of_shape[f];
    for (int n : faces_of_shape) CHECK(n > 0);
    // vertex_shape names the shape of each grey vertex; a face's shape is one of its vertices'.
    REQUIRE(s.vertex_shape.size() == s.mesh.positions.size());
    for (int v = 0; v < s.mesh.num_vertices(); ++v)
        CHECK((s.vertex_grey[v] > 0) == (s.vertex_shape[v] >= 0));
    for (int f = 0; f < s.mesh.num_faces(); ++f)
        if (s.face_shape[f] >= 0) {
            const auto& fv = s.mesh.faces[f];
            CHECK((s.vertex_shape[fv[0]] == s.face_shape[f] ||
                   s.vertex_shape[fv[1]] == s.face_shape[f] ||
                   s.vertex_shape[fv[2]] == s.face_shape[f]));
        }
}

TEST_CASE("make_synthetic_sphere: deterministic; noise bounded and seeded", "[geometry][synth]") {
    SynthParams p;
    p.level = 4;
    const SyntheticMesh a = make_synthetic_sphere(p), b = make_synthetic_sphere(p);
    CHECK(a.mesh.positions == b.mesh.positions);
    CHECK(a.face_shape == b.face_shape);
    p.noise_percent = 0.3;
    const SyntheticMesh n1 = make_synthetic_sphere(p);
    p.noise_seed = 2;
    const SyntheticMesh n2 = make_synthetic_sphere(p);
    CHECK(n1.mesh.positions != n2.mesh.positions);
    CHECK(n1.face_shape == a.face_shape);  // the noise does not move the ground truth
    for (int v = 0; v < a.mesh.num_vertices(); ++v)
        CHECK(std::abs(n1.mesh.positions[v].norm() - a.mesh.positions[v].norm()) <= 0.003 + 1e-12);
}

TEST_CASE("make_synthetic_sphere: engraved shapes go inward", "[geometry][synth]") {
    SynthParams p;
    p.level = 4;
    p.engraved_fraction = 0.5;
    const SyntheticMesh s = make_synthetic_sphere(p);
    int engraved = 0;
    for (const auto& shape : s.shapes) engraved += shape.engraved;
    CHECK(engraved == 44);
    double lowest = 2;
    for (const auto& q : s.mesh.positions) lowest = std::min(lowest, q.norm());
    CHECK(lowest < 0.99);
}

TEST_CASE("make_synthetic_sphere: preconditions", "[geometry][synth]") {
    SynthParams p;
    p.level = 12;  // 335 million faces: beyond what make_icosphere builds
    REQUIRE_THROWS_AS(make_synthetic_sphere(p), InvalidInput);
    p.level = 3;
    p.num_big_discs = 5000;  // cannot fit
    REQUIRE_THROWS_AS(make_synthetic_sphere(p), InvalidInput);
    p.num_big_discs = 1;
    p.noise_percent = -1;
    REQUIRE_THROWS_AS(make_synthetic_sphere(p), InvalidInput);
}
