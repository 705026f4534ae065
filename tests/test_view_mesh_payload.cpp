// GTXM (view/README.md): the bytes of a small segmentation decoded field by field and
// compared with the polygons, ids and depths they were made from; and the thumbnail's PNG.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>

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

TEST_CASE("make_mesh_payload: header, fans and per-triangle values", "[view][mesh_payload]") {
    const MeshFile file = read_mesh_memory(kSegmentation, "seg.ply");
    const std::vector<double> depth = {0.125, -0.5};
    const std::string b = view::make_mesh_payload(file, depth, "seg.ply");
    // Fans: quad 2 triangles, triangle 1, pentagon 3.
    const std::uint32_t nv = 6, nf = 6;
    REQUIRE(b.size() == 16 + nv * 12 + nf * 12 + nf * 12);
    CHECK(b.substr(0, 4) == "GTXM");
    CHECK(field<std::uint32_t>(b, 4) == 1);
    CHECK(field<std::uint32_t>(b, 8) == nv);
    CHECK(field<std::uint32_t>(b, 12) == nf);
    const double positions[6][3] = {{0, 0, 0}, {1, 0, 0},      {1, 1, 0},
                                    {0, 1, 0}, {0.5, 2, 0.25}, {-0.5, 1.5, -1}};
    for (std::size_t v = 0; v < nv; ++v)
        for (std::size_t k = 0; k < 3; ++k)
            CHECK(field<float>(b, 16 + 12 * v + 4 * k) == static_cast<float>(positions[v][k]));
    const std::size_t idx = 16 + nv * 12;
    const std::uint32_t triangles[6][3] = {{0, 1, 2}, {0, 2, 3}, {3, 2, 4},
                                           {0, 3, 5}, {0, 5, 4}, {0, 4, 1}};
    for (std::size_t t = 0; t < nf; ++t)
        for (std::size_t k = 0; k < 3; ++k)
            CHECK(field<std::uint32_t>(b, idx + 12 * t + 4 * k) == triangles[t][k]);
    const std::size_t texel = idx + nf * 12, texture = texel + nf * 4, depths = texture + nf * 4;
    const int texels[6] = {1, 1, -1, 0, 0, 0};
    const int textures[6] = {0, 0, -1, 1, 1, 1};
    for (std::size_t t = 0; t < nf; ++t) {
        CHECK(field<std::int32_t>(b, texel + 4 * t) == texels[t]);
        CHECK(field<std::int32_t>(b, texture + 4 * t) == textures[t]);
        const float d = field<float>(b, depths + 4 * t);
        if (texels[t] < 0)
            CHECK(std::isnan(d));
        else
            CHECK(d == static_cast<float>(depth[static_cast<std::size_t>(texels[t])]));
    }
}

TEST_CASE("make_mesh_payload: a mesh without segmentation has -1 everywhere",
          "[view][mesh_payload]") {
    const MeshFile file = read_mesh_memory(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        "plain.ply");
    const std::string b = view::make_mesh_payload(file, {}, "plain.ply");
    REQUIRE(b.size() == 16 + 36 + 12 + 12);
    CHECK(field<std::int32_t>(b, 16 + 36 + 12) == -1);
    CHECK(field<std::int32_t>(b, 16 + 36 + 16) == -1);
    CHECK(std::isnan(field<float>(b, 16 + 36 + 20)));
}

TEST_CASE("make_mesh_payload: refuses texels the report does not have", "[view][mesh_payload]") {
    const MeshFile file = read_mesh_memory(kSegmentation, "seg.ply");
    REQUIRE_THROWS_AS(view::make_mesh_payload(file, {0.1}, "seg.ply"), InvalidInput);
    MeshFile bad = file;
    for (auto& p : bad.face_properties)
        if (p.name == "texture") p.values[0] = 0.5;
    REQUIRE_THROWS_AS(view::make_mesh_payload(bad, {0.1, 0.2}, "seg.ply"), InvalidInput);
    for (auto& p : bad.face_properties)
        if (p.name == "texture") p.values[0] = -2;
    REQUIRE_THROWS_AS(view::make_mesh_payload(bad, {0.1, 0.2}, "seg.ply"), InvalidInput);
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
