#include "pipeline/tile_mesh.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>

#include "common/errors.hpp"
#include "pipeline/detail/framed_file.hpp"

namespace geotex {

namespace {

using detail::bits_of;
using detail::Cbor;
using detail::double_of;
using detail::point_of;
constexpr int kTileMeshSchema = 1;
const std::string kTileMeshMagic = "geotex tile mesh\n";
constexpr const char* kTileMeshKind = "tile mesh";

// A vertex's flags, one bit each in its byte.
constexpr std::uint64_t kOwned = 1, kComplete = 2, kFast = 4;

// Bytes a vertex and a face (the header's comment).
constexpr std::uint64_t kVertexBytes = 24 + 4 + 1 + 4, kFaceBytes = 12 + 4 + 1;

// An id read back, refused unless it is above the one before it.
int ascending_id(std::uint64_t bits, std::size_t i, int before, const char* what) {
    if (bits > static_cast<std::uint64_t>(INT32_MAX) || (i > 0 && static_cast<int>(bits) <= before))
        throw InvalidInput(std::string("damaged: the ids of its ") + what + " do not ascend");
    return static_cast<int>(bits);
}

}  // namespace

void write_tile_mesh(std::ostream& out, const std::string& key, const DepthTile& numbers,
                     const DepthTileRows& rows) {
    const Eigen::Vector3d& o = numbers.sampling.origin;
    const std::size_t nv = rows.num_vertices(), nf = rows.num_faces();
    const Cbor header = {{"schema", kTileMeshSchema},
                         {"key", key},
                         {"tile", numbers.tile},
                         {"boxes",
                          {{"lo", bits_of(numbers.boxes.lo)},
                           {"hi", bits_of(numbers.boxes.hi)},
                           {"count", numbers.boxes.count}}},
                         {"mesh_vertices", numbers.mesh_vertices},
                         {"radius", bits_of(numbers.radius)},
                         {"halo", bits_of(numbers.halo)},
                         {"vertices", nv},
                         {"faces", nf},
                         {"components", numbers.components.num_components},
                         {"sampling_origin", bits_of(o)},
                         {"sampling_grid", numbers.sampling.grid}};
    detail::write_framed_header(out, kTileMeshMagic, header);
    const auto u32 = [](int value) {
        return static_cast<std::uint64_t>(static_cast<std::uint32_t>(value));
    };
    // Each array is written whole before the next; the faces' three are read back a block at
    // a time for each, from where the rows keep them.
    detail::write_values(out, 3 * nv, 8, [&](std::size_t i) {
        return bits_of(rows.position(i / 3)[static_cast<int>(i % 3)]);
    });
    detail::write_values(out, nv, 4, [&](std::size_t i) { return u32(rows.vertex_id(i)); });
    detail::write_values(out, nv, 1, [&](std::size_t i) {
        return (rows.owned_vertex(i) ? kOwned : 0) | (rows.complete_vertex(i) ? kComplete : 0) |
               (rows.fast(i) ? kFast : 0);
    });
    detail::write_values(out, nv, 4, [&](std::size_t i) { return u32(rows.component(i)); });
    rows.for_each_face_block([&](const TileFaceBlock& block) {
        detail::write_values(out, 3 * block.faces.size(), 4,
                             [&](std::size_t i) { return u32(block.faces[i / 3][i % 3]); });
    });
    rows.for_each_face_block([&](const TileFaceBlock& block) {
        detail::write_values(out, block.ids.size(), 4,
                             [&](std::size_t i) { return u32(block.ids[i]); });
    });
    rows.for_each_face_block([&](const TileFaceBlock& block) {
        detail::write_values(out, block.owned.size(), 1,
                             [&](std::size_t i) { return block.owned[i] ? kOwned : 0; });
    });
}

void write_tile_mesh(std::ostream& out, const std::string& key, const DepthTile& tile) {
    write_tile_mesh(out, key, tile, *held_rows(tile));
}

namespace {

// The tile's numbers from its header, checked, with its counts of vertices and faces; `in` is
// left at the start of the arrays.
DepthTile read_numbers(std::istream& in, const std::string& key, int tile, std::size_t& nv,
                       std::size_t& nf) {
    const Cbor header =
        detail::read_framed_header(in, kTileMeshMagic, kTileMeshKind, kTileMeshSchema, key);
    DepthTile out;
    try {
        out.tile = header.at("tile").get<int>();
        const Cbor& boxes = header.at("boxes");
        out.boxes.lo = point_of(boxes.at("lo"));
        out.boxes.hi = point_of(boxes.at("hi"));
        out.boxes.count = boxes.at("count").get<std::array<int, 3>>();
        out.mesh_vertices = header.at("mesh_vertices").get<int>();
        out.radius = double_of(header.at("radius").get<std::uint64_t>());
        out.halo = double_of(header.at("halo").get<std::uint64_t>());
        nv = header.at("vertices").get<std::size_t>();
        nf = header.at("faces").get<std::size_t>();
        out.components.num_components = header.at("components").get<int>();
        out.sampling.origin = point_of(header.at("sampling_origin"));
        out.sampling.grid = header.at("sampling_grid").get<bool>();
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")");
    }
    if (out.tile != tile)
        throw InvalidInput("the mesh of tile " + std::to_string(out.tile + 1) + ", not of tile " +
                           std::to_string(tile + 1));
    if (!(out.radius > 0) || !std::isfinite(out.radius) || !(out.halo >= 0) ||
        !std::isfinite(out.halo) || !out.sampling.origin.allFinite() || !out.boxes.lo.allFinite() ||
        !out.boxes.hi.allFinite())
        throw InvalidInput(
            "damaged: the radius, the halo, the boxes or the sampling grid is not finite");
    for (int c : out.boxes.count)
        if (c < 1 || c > 1 << 20) throw InvalidInput("damaged: the boxes' counts are out of range");
    if (tile >= out.boxes.size())
        throw InvalidInput("the mesh of a run of " + std::to_string(out.boxes.size()) +
                           " tiles, not of tile " + std::to_string(tile + 1));
    // Indices are 32-bit and every index below nv; more vertices than that cannot be named.
    if (nv > static_cast<std::size_t>(INT32_MAX) || nf > static_cast<std::size_t>(INT32_MAX) ||
        out.components.num_components < 0 || out.mesh_vertices < 0)
        throw InvalidInput("damaged: the counts are out of range");
    detail::expect_bytes_left(in, kVertexBytes * nv + kFaceBytes * nf);
    return out;
}

}  // namespace

DepthTile read_tile_mesh_numbers(std::istream& in, const std::string& key, int tile) {
    std::size_t nv = 0, nf = 0;
    return read_numbers(in, key, tile, nv, nf);
}

DepthTile read_tile_mesh(std::istream& in, const std::string& key, int tile) {
    std::size_t nv = 0, nf = 0;
    DepthTile out = read_numbers(in, key, tile, nv, nf);
    MeshTile& t = out.mesh;
    t.mesh.positions.resize(nv);
    detail::read_values(in, 3 * nv, 8, [&](std::size_t i, std::uint64_t bits) {
        const double x = double_of(bits);
        if (!std::isfinite(x))
            throw InvalidInput("damaged: vertex " + std::to_string(i / 3) +
                               " has a coordinate that is not finite");
        t.mesh.positions[i / 3][static_cast<int>(i % 3)] = x;
    });
    t.vertex.resize(nv);
    detail::read_values(in, nv, 4, [&](std::size_t i, std::uint64_t bits) {
        t.vertex[i] = ascending_id(bits, i, i > 0 ? t.vertex[i - 1] : 0, "vertices");
    });
    t.owned_vertex.resize(nv);
    t.complete_vertex.resize(nv);
    out.sampling.fast.resize(nv);
    detail::read_values(in, nv, 1, [&](std::size_t i, std::uint64_t bits) {
        if (bits & ~(kOwned | kComplete | kFast))
            throw InvalidInput("damaged: vertex " + std::to_string(i) + "'s flags are unknown");
        t.owned_vertex[i] = (bits & kOwned) ? 1 : 0;
        t.complete_vertex[i] = (bits & kComplete) ? 1 : 0;
        out.sampling.fast[i] = (bits & kFast) ? 1 : 0;
    });
    out.components.component.resize(nv);
    detail::read_values(in, nv, 4, [&](std::size_t i, std::uint64_t bits) {
        if (bits >= static_cast<std::uint64_t>(out.components.num_components))
            throw InvalidInput("damaged: vertex " + std::to_string(i) +
                               "'s component is out of range");
        out.components.component[i] = static_cast<int>(bits);
    });
    t.mesh.faces.resize(nf);
    detail::read_values(in, 3 * nf, 4, [&](std::size_t i, std::uint64_t bits) {
        if (bits >= nv)
            throw InvalidInput("damaged: face " + std::to_string(i / 3) +
                               " names a vertex past the last");
        t.mesh.faces[i / 3][i % 3] = static_cast<int>(bits);
    });
    if (nv > 0 && t.vertex.back() >= out.mesh_vertices)
        throw InvalidInput("damaged: a vertex id is past the mesh's vertices");
    t.face.resize(nf);
    detail::read_values(in, nf, 4, [&](std::size_t i, std::uint64_t bits) {
        t.face[i] = ascending_id(bits, i, i > 0 ? t.face[i - 1] : 0, "faces");
    });
    t.owned_face.resize(nf);
    detail::read_values(in, nf, 1, [&](std::size_t i, std::uint64_t bits) {
        if (bits & ~kOwned)
            throw InvalidInput("damaged: face " + std::to_string(i) + "'s flags are unknown");
        t.owned_face[i] = bits ? 1 : 0;
    });
    return out;
}

}  // namespace geotex
