// GTXM (view/README.md): the bytes of a small segmentation decoded field by field and
// compared with the polygons, ids and depths they were made from; and the thumbnail's PNG.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "common/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "view/mesh_payload.hpp"
#include "view/thumbnail.hpp"

using namespace geotex;

namespace {

// A quad (texel 1, texture 0), a triangle (no texel, no texture) and a pentagon (texel 0,
// texture 1), as geotex segment writes them (face properties texel and texture).
const char* kSegmentation =
    "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
    "property float z\nelement face 3\nproperty list uchar int vertex_indices\n"
    "property int texel\nproperty int texture\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 2 0.25\n-0.5 1.5 -1\n"
    "4 0 1 2 3 1 0\n3 3 2 4 -1 -1\n5 0 3 5 4 1 0 1\n";

// Reads the little-endian 32-bit field at `offset`.
template <typename T>
T field(const std::string& bytes, std::size_t offset) {
    REQUIRE(offset + 4 <= bytes.size());
    std::uint32_t bits = 0;
    for (int k = 3; k >= 0; --k)
        bits =
            (bits << 8) | static_cast<unsigned char>(bytes[offset + static_cast<std::size_t>(k)]);
    T value;
    std::memcpy(&value, &bits, 4);
    return value;
}

}  // namespace

TEST_CASE("make_mesh_payload: header, fans, vertices split at texel borders, texel tables",
          "[view][mesh_payload]") {
    const MeshFile file = read_mesh_memory(kSegmentation, "seg.ply");
    const std::vector<double> depth = {0.125, -0.5};
    const std::string b = view::make_mesh_payload(file, depth, "seg.ply");
    // Fans: quad 2 triangles, triangle 1, pentagon 3. Vertices: one per (file vertex, texel)
    // pair that a face uses: 0 {1, 0}, 1 {1, 0}, 2 {1, -1}, 3 {1, -1, 0}, 4 {-1, 0}, 5 {0}.
    const std::uint32_t nv = 12, nf = 6, nt = 2;
    REQUIRE(b.size() == 20 + nv * 12 + nf * 12 + nf * 4 + nt * 8);
    CHECK(b.substr(0, 4) == "GTXM");
    CHECK(field<std::uint32_t>(b, 4) == 2);
    CHECK(field<std::uint32_t>(b, 8) == nv);
    CHECK(field<std::uint32_t>(b, 12) == nf);
    CHECK(field<std::uint32_t>(b, 16) == nt);
    const std::size_t pos = 20, idx = pos + nv * 12, texel = idx + nf * 12;
    const std::size_t texture = texel + nf * 4, depths = texture + nt * 4;
    const double positions[6][3] = {{0, 0, 0}, {1, 0, 0},      {1, 1, 0},
                                    {0, 1, 0}, {0.5, 2, 0.25}, {-0.5, 1.5, -1}};
    // The file's vertices come first, unchanged.
    for (std::size_t v = 0; v < 6; ++v)
        for (std::size_t k = 0; k < 3; ++k)
            CHECK(field<float>(b, pos + 12 * v + 4 * k) == static_cast<float>(positions[v][k]));
    const std::uint32_t triangles[6][3] = {{0, 1, 2}, {0, 2, 3}, {3, 2, 4},
                                           {0, 3, 5}, {0, 5, 4}, {0, 4, 1}};
    const int texels[6] = {1, 1, -1, 0, 0, 0};
    // Each corner is at its file vertex's position, and no payload vertex serves two texels.
    std::vector<int> texel_of_vertex(nv, -2);
    for (std::size_t t = 0; t < nf; ++t) {
        CHECK(field<std::int32_t>(b, texel + 4 * t) == texels[t]);
        for (std::size_t k = 0; k < 3; ++k) {
            const auto v = field<std::uint32_t>(b, idx + 12 * t + 4 * k);
            REQUIRE(v < nv);
            for (std::size_t c = 0; c < 3; ++c)
                CHECK(field<float>(b, pos + 12 * v + 4 * c) ==
                      static_cast<float>(positions[triangles[t][k]][c]));
            if (texel_of_vertex[v] == -2) texel_of_vertex[v] = texels[t];
            CHECK(texel_of_vertex[v] == texels[t]);
        }
    }
    // Every vertex is used (12 pairs, 12 vertices), and the quad keeps the file's indices.
    for (std::size_t v = 0; v < nv; ++v) CHECK(texel_of_vertex[v] != -2);
    CHECK(field<std::uint32_t>(b, idx) == 0);
    CHECK(field<std::uint32_t>(b, idx + 4) == 1);
    CHECK(field<std::uint32_t>(b, idx + 8) == 2);
    // Texel 0 is the pentagon (texture 1), texel 1 the quad (texture 0).
    CHECK(field<std::int32_t>(b, texture) == 1);
    CHECK(field<std::int32_t>(b, texture + 4) == 0);
    CHECK(field<float>(b, depths) == 0.125f);
    CHECK(field<float>(b, depths + 4) == -0.5f);
}

TEST_CASE("make_mesh_payload: a mesh without segmentation has no texel", "[view][mesh_payload]") {
    const MeshFile file = read_mesh_memory(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        "plain.ply");
    const std::string b = view::make_mesh_payload(file, {}, "plain.ply");
    REQUIRE(b.size() == 20 + 36 + 12 + 4);
    CHECK(field<std::uint32_t>(b, 16) == 0);
    CHECK(field<std::int32_t>(b, 20 + 36 + 12) == -1);
}

TEST_CASE("make_mesh_payload: refuses texels the report does not have, and mixed textures",
          "[view][mesh_payload]") {
    const MeshFile file = read_mesh_memory(kSegmentation, "seg.ply");
    REQUIRE_THROWS_AS(view::make_mesh_payload(file, {0.1}, "seg.ply"), InvalidInput);
    const auto with_texture = [&](std::size_t polygon, double value) {
        MeshFile bad = file;
        for (auto& p : bad.face_properties)
            if (p.name == "texture") p.values[polygon] = value;
        return bad;
    };
    REQUIRE_THROWS_AS(view::make_mesh_payload(with_texture(0, 0.5), {0.1, 0.2}, "seg.ply"),
                      InvalidInput);
    REQUIRE_THROWS_AS(view::make_mesh_payload(with_texture(0, -2), {0.1, 0.2}, "seg.ply"),
                      InvalidInput);
    // The triangle is in no texel: it cannot be in a texture.
    REQUIRE_THROWS_WITH(view::make_mesh_payload(with_texture(1, 0), {0.1, 0.2}, "seg.ply"),
                        Catch::Contains("in no texel"));
    // Texel 1 (the quad) in two textures: add a polygon of texel 1 in texture 1.
    MeshFile two = file;
    for (int v : {0, 1, 5}) two.soup.face_indices.push_back(v);
    two.soup.face_offsets.push_back(static_cast<int>(two.soup.face_indices.size()));
    for (auto& p : two.face_properties) p.values.push_back(1);
    REQUIRE_THROWS_WITH(view::make_mesh_payload(two, {0.1, 0.2}, "seg.ply"),
                        Catch::Contains("texel 1 has faces in textures 0 and 1"));
}

TEST_CASE("make_thumbnail: a 192 by 192 PNG, the same bytes each time", "[view][thumbnail]") {
    const MeshFile file = read_mesh_memory(kSegmentation, "seg.ply");
    const std::string png = view::make_thumbnail(file, "seg.ply");
    REQUIRE(png.size() > 33);
    CHECK(png.substr(0, 8) == "\x89PNG\r\n\x1a\n");
    CHECK(png.substr(12, 4) == "IHDR");
    // IHDR's width and height are big-endian 32-bit numbers.
    auto be32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(png[at + k]);
        return v;
    };
    CHECK(be32(16) == static_cast<std::uint32_t>(view::kThumbnailSide));
    CHECK(be32(20) == static_cast<std::uint32_t>(view::kThumbnailSide));
    CHECK(view::make_thumbnail(file, "seg.ply") == png);
}
