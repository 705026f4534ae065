#include "pipeline/prepared_mesh.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <istream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "pipeline/detail/little_endian.hpp"

namespace geotex {

namespace {

using detail::bits_of;
using detail::double_of;
using detail::get_le;
using detail::put_le;
using Cbor = nlohmann::json;  // the header, through the library's CBOR writer and reader
constexpr int kSchema = 1;
constexpr const char* kMagic = "geotex prepared mesh\n";
constexpr std::size_t kMagicSize = 21;
// A header is a few hundred bytes; a larger length is a damaged file, not a reason to
// allocate gigabytes.
constexpr std::uint64_t kMaxHeader = 1 << 20;

// The report's counts under the names the file gives them.
constexpr std::array<std::pair<const char*, int MeshRepairReport::*>, 12> kReportCounts = {{
    {"input_vertices", &MeshRepairReport::num_input_vertices},
    {"input_polygons", &MeshRepairReport::num_input_polygons},
    {"polygons_triangulated", &MeshRepairReport::num_polygons_triangulated},
    {"duplicate_vertices_merged", &MeshRepairReport::num_duplicate_vertices_merged},
    {"degenerate_faces_removed", &MeshRepairReport::num_degenerate_faces_removed},
    {"duplicate_faces_removed", &MeshRepairReport::num_duplicate_faces_removed},
    {"faces_flipped", &MeshRepairReport::num_faces_flipped},
    {"isolated_vertices", &MeshRepairReport::num_isolated_vertices},
    {"boundary_edges", &MeshRepairReport::num_boundary_edges},
    {"non_manifold_edges", &MeshRepairReport::num_non_manifold_edges},
    {"components", &MeshRepairReport::num_components},
    {"closed_components", &MeshRepairReport::num_closed_components},
}};

// Values are packed little-endian (detail/little_endian.hpp) a block at a time, so that
// neither side holds a second copy of an array.
constexpr std::size_t kBlockValues = 1 << 16;

// Writes `count` values, value(i) giving the i-th as its bits, each `size` bytes.
template <class Fn>
void write_values(std::ostream& out, std::size_t count, std::size_t size, Fn&& value) {
    std::vector<std::uint8_t> block(kBlockValues * size);
    for (std::size_t begin = 0; begin < count; begin += kBlockValues) {
        const std::size_t n = std::min(kBlockValues, count - begin);
        for (std::size_t i = 0; i < n; ++i) put_le(&block[i * size], value(begin + i), size);
        out.write(reinterpret_cast<const char*>(block.data()),
                  static_cast<std::streamsize>(n * size));
    }
}

// Reads `count` values of `size` bytes, handing each to take(i, bits).
template <class Fn>
void read_values(std::istream& in, std::size_t count, std::size_t size, Fn&& take) {
    std::vector<std::uint8_t> block(kBlockValues * size);
    for (std::size_t begin = 0; begin < count; begin += kBlockValues) {
        const std::size_t n = std::min(kBlockValues, count - begin);
        if (!in.read(reinterpret_cast<char*>(block.data()), static_cast<std::streamsize>(n * size)))
            throw InvalidInput("damaged: the file ends inside its arrays");
        for (std::size_t i = 0; i < n; ++i) take(begin + i, get_le(&block[i * size], size));
    }
}

}  // namespace

void write_prepared_mesh(std::ostream& out, const std::string& key, const PreparedMesh& mesh) {
    const Mesh& m = mesh.repaired.mesh;
    Cbor header = {{"schema", kSchema},
                   {"key", key},
                   {"vertices", m.positions.size()},
                   {"faces", m.faces.size()},
                   {"format", mesh.format}};
    for (const auto& [name, member] : kReportCounts)
        header["report"][name] = mesh.repaired.report.*member;
    header["notes"] = Cbor::array();
    for (const Diagnostic& d : mesh.repaired.diagnostics)
        header["notes"].push_back({{"stage", d.stage}, {"message", d.message}});
    const std::vector<std::uint8_t> bytes = Cbor::to_cbor(header);
    out.write(kMagic, kMagicSize);
    std::uint8_t length[8];
    put_le(length, bytes.size(), 8);
    out.write(reinterpret_cast<const char*>(length), 8);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    write_values(out, 3 * m.positions.size(), 8, [&](std::size_t i) {
        return bits_of(m.positions[i / 3][static_cast<int>(i % 3)]);
    });
    write_values(out, 3 * m.faces.size(), 4, [&](std::size_t i) {
        return static_cast<std::uint64_t>(static_cast<std::uint32_t>(m.faces[i / 3][i % 3]));
    });
}

PreparedMesh read_prepared_mesh(std::istream& in, const std::string& key) {
    char magic[kMagicSize];
    if (!in.read(magic, kMagicSize) || std::memcmp(magic, kMagic, kMagicSize) != 0)
        throw InvalidInput("not a geotex prepared mesh");
    std::uint8_t length[8];
    if (!in.read(reinterpret_cast<char*>(length), 8))
        throw InvalidInput("damaged: the file ends in its header");
    const std::uint64_t header_size = get_le(length, 8);
    if (header_size > kMaxHeader) throw InvalidInput("damaged: the header's length is wrong");
    std::vector<std::uint8_t> bytes(header_size);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(header_size)))
        throw InvalidInput("damaged: the file ends in its header");
    PreparedMesh mesh;
    std::size_t nv = 0, nf = 0;
    try {
        const Cbor header = Cbor::from_cbor(bytes);
        if (header.at("schema").get<int>() != kSchema)
            throw InvalidInput("a prepared mesh of schema " + header.at("schema").dump() +
                               ", not " + std::to_string(kSchema) + " (made by another geotex)");
        if (header.at("key").get<std::string>() != key)
            throw InvalidInput(
                "the mesh of another run: another mesh, other options, another number of tiles "
                "or another geotex");
        nv = header.at("vertices").get<std::size_t>();
        nf = header.at("faces").get<std::size_t>();
        mesh.format = header.at("format").get<std::string>();
        for (const auto& [name, member] : kReportCounts)
            mesh.repaired.report.*member = header.at("report").at(name).get<int>();
        for (const Cbor& note : header.at("notes"))
            mesh.repaired.diagnostics.push_back(
                {note.at("stage").get<std::string>(), note.at("message").get<std::string>()});
    } catch (const InvalidInput&) {
        throw;
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")");
    }
    // Indices are 32-bit and every index below nv; more vertices than that cannot be named.
    if (nv > static_cast<std::size_t>(INT32_MAX) || nf > static_cast<std::size_t>(INT32_MAX))
        throw InvalidInput("damaged: the counts are out of range");
    // The counts are checked against the file's size before the arrays are made, so that a
    // damaged count is an error, not an allocation of its size.
    const std::istream::pos_type here = in.tellg();
    in.seekg(0, std::ios::end);
    const std::istream::pos_type end = in.tellg();
    in.seekg(here);
    if (here == std::istream::pos_type(-1) || end == std::istream::pos_type(-1))
        throw InvalidInput("cannot measure the file");
    const std::uint64_t expected =
        24 * static_cast<std::uint64_t>(nv) + 12 * static_cast<std::uint64_t>(nf);
    const auto left = static_cast<std::uint64_t>(end - here);
    if (left < expected) throw InvalidInput("damaged: the file ends inside its arrays");
    if (left > expected) throw InvalidInput("damaged: bytes past the end of the faces");
    Mesh& m = mesh.repaired.mesh;
    m.positions.resize(nv);
    m.faces.resize(nf);
    read_values(in, 3 * nv, 8, [&](std::size_t i, std::uint64_t bits) {
        const double x = double_of(bits);
        if (!std::isfinite(x))
            throw InvalidInput("damaged: vertex " + std::to_string(i / 3) +
                               " has a coordinate that is not finite");
        m.positions[i / 3][static_cast<int>(i % 3)] = x;
    });
    read_values(in, 3 * nf, 4, [&](std::size_t i, std::uint64_t bits) {
        if (bits >= nv)
            throw InvalidInput("damaged: face " + std::to_string(i / 3) +
                               " names a vertex past the last");
        m.faces[i / 3][i % 3] = static_cast<int>(bits);
    });
    return mesh;
}

}  // namespace geotex
