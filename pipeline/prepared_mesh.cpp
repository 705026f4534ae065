#include "pipeline/prepared_mesh.hpp"

#include <algorithm>
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
#include "pipeline/detail/framed_file.hpp"

namespace geotex {

namespace {

using detail::bits_of;
using detail::Cbor;
using detail::double_of;
constexpr int kSchema = 1;
const std::string kMagic = "geotex prepared mesh\n";
constexpr const char* kKind = "prepared mesh";

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

}  // namespace

void write_prepared_mesh(std::ostream& out, const std::string& key, const PreparedMesh& mesh) {
    const Mesh& m = mesh.repaired.mesh;
    write_prepared_mesh(out, key, mesh, m.positions, face_reader(m.faces), m.faces.size());
}

void write_prepared_mesh(std::ostream& out, const std::string& key, const PreparedMesh& mesh,
                         PositionSpan positions, const FaceBlockReader& faces,
                         std::size_t num_faces) {
    Cbor header = {{"schema", kSchema},
                   {"key", key},
                   {"vertices", positions.size()},
                   {"faces", num_faces},
                   {"format", mesh.format}};
    for (const auto& [name, member] : kReportCounts)
        header["report"][name] = mesh.repaired.report.*member;
    header["notes"] = Cbor::array();
    for (const Diagnostic& d : mesh.repaired.diagnostics)
        header["notes"].push_back({{"stage", d.stage}, {"message", d.message}});
    detail::write_framed_header(out, kMagic, header);
    detail::write_values(out, 3 * positions.size(), 8, [&](std::size_t i) {
        return bits_of(positions[i / 3][static_cast<int>(i % 3)]);
    });
    for_each_face_block(faces, num_faces, [&](std::size_t, const auto& block) {
        detail::write_values(out, 3 * block.size(), 4, [&](std::size_t i) {
            return static_cast<std::uint64_t>(static_cast<std::uint32_t>(block[i / 3][i % 3]));
        });
    });
}

PreparedOutline read_prepared_outline(std::istream& in, const std::string& key,
                                      PositionFile* positions) {
    const Cbor header = detail::read_framed_header(in, kMagic, kKind, kSchema, key);
    PreparedOutline outline;
    PreparedMesh& mesh = outline.mesh;
    std::size_t nv = 0, nf = 0;
    try {
        nv = header.at("vertices").get<std::size_t>();
        nf = header.at("faces").get<std::size_t>();
        mesh.format = header.at("format").get<std::string>();
        for (const auto& [name, member] : kReportCounts)
            mesh.repaired.report.*member = header.at("report").at(name).get<int>();
        for (const Cbor& note : header.at("notes"))
            mesh.repaired.diagnostics.push_back(
                {note.at("stage").get<std::string>(), note.at("message").get<std::string>()});
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")");
    }
    // Indices are 32-bit and every index below nv; more vertices than that cannot be named.
    if (nv > static_cast<std::size_t>(INT32_MAX) || nf > static_cast<std::size_t>(INT32_MAX))
        throw InvalidInput("damaged: the counts are out of range");
    detail::expect_bytes_left(
        in, 24 * static_cast<std::uint64_t>(nv) + 12 * static_cast<std::uint64_t>(nf));
    Mesh& m = mesh.repaired.mesh;
    if (!positions) m.positions.resize(nv);
    Eigen::Vector3d p;
    detail::read_values(in, 3 * nv, 8, [&](std::size_t i, std::uint64_t bits) {
        const double x = double_of(bits);
        if (!std::isfinite(x))
            throw InvalidInput("damaged: vertex " + std::to_string(i / 3) +
                               " has a coordinate that is not finite");
        p[static_cast<int>(i % 3)] = x;
        if (i % 3 != 2) return;
        if (positions)
            positions->append(p);
        else
            m.positions[i / 3] = p;
    });
    outline.num_vertices = nv;
    outline.num_faces = nf;
    outline.faces_at = static_cast<std::uint64_t>(in.tellg());
    return outline;
}

void read_prepared_faces(std::istream& in, const PreparedOutline& outline, std::size_t first,
                         std::size_t count, std::vector<std::array<int, 3>>& out) {
    if (first > outline.num_faces || count > outline.num_faces - first)
        throw InvalidInput("faces " + std::to_string(first) + " to " +
                           std::to_string(first + count) + " are past the last face");
    in.clear();
    in.seekg(
        static_cast<std::streamoff>(outline.faces_at + 12 * static_cast<std::uint64_t>(first)));
    const std::size_t nv = outline.num_vertices;
    out.resize(count);
    // A face at a time rather than detail::read_values' value at a time: the mesh job reads
    // every face once a tile, and this loop was a seventh of its processor time.
    constexpr std::size_t kFaces = detail::kBlockValues / 3;
    std::vector<std::uint8_t> block(std::min(count, kFaces) * 12);
    for (std::size_t begin = 0; begin < count; begin += kFaces) {
        const std::size_t n = std::min(kFaces, count - begin);
        if (!in.read(reinterpret_cast<char*>(block.data()), static_cast<std::streamsize>(n * 12)))
            throw InvalidInput("damaged: the file ends inside its arrays");
        std::uint64_t largest = 0;
        for (std::size_t k = 0; k < n; ++k)
            for (std::size_t c = 0; c < 3; ++c) {
                const std::uint64_t bits = detail::get_le(&block[12 * k + 4 * c], 4);
                largest = std::max(largest, bits);
                out[begin + k][c] = static_cast<int>(bits);
            }
        if (largest < nv) continue;
        for (std::size_t k = 0; k < n; ++k)
            for (int v : out[begin + k])
                if (static_cast<std::uint32_t>(v) >= nv)
                    throw InvalidInput("damaged: face " + std::to_string(first + begin + k) +
                                       " names a vertex past the last");
    }
}

namespace {

constexpr int kExtentSchema = 1;
const std::string kExtentMagic = "geotex mesh extent\n";
constexpr const char* kExtentKind = "mesh extent";

}  // namespace

void write_mesh_extent(std::ostream& out, const std::string& key, const MeshMetrics& extent) {
    detail::write_framed_header(out, kExtentMagic,
                                {{"schema", kExtentSchema},
                                 {"key", key},
                                 {"bbox_min", bits_of(extent.bbox_min)},
                                 {"bbox_max", bits_of(extent.bbox_max)},
                                 {"largest_side", bits_of(extent.largest_side)},
                                 {"mean_edge_length", bits_of(extent.mean_edge_length)},
                                 {"vertices", extent.num_vertices},
                                 {"faces", extent.num_faces}});
}

MeshMetrics read_mesh_extent(std::istream& in, const std::string& key) {
    const Cbor header =
        detail::read_framed_header(in, kExtentMagic, kExtentKind, kExtentSchema, key);
    MeshMetrics m;
    try {
        m.bbox_min = detail::point_of(header.at("bbox_min"));
        m.bbox_max = detail::point_of(header.at("bbox_max"));
        m.largest_side = double_of(header.at("largest_side").get<std::uint64_t>());
        m.mean_edge_length = double_of(header.at("mean_edge_length").get<std::uint64_t>());
        m.num_vertices = header.at("vertices").get<int>();
        m.num_faces = header.at("faces").get<int>();
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")");
    }
    if (!m.bbox_min.allFinite() || !m.bbox_max.allFinite() || !std::isfinite(m.largest_side) ||
        !std::isfinite(m.mean_edge_length) || m.num_vertices < 0 || m.num_faces < 0)
        throw InvalidInput("damaged: a number is not finite, or a count is negative");
    detail::expect_bytes_left(in, 0);
    return m;
}

PreparedMesh read_prepared_mesh(std::istream& in, const std::string& key) {
    PreparedOutline outline = read_prepared_outline(in, key);
    read_prepared_faces(in, outline, 0, outline.num_faces, outline.mesh.repaired.mesh.faces);
    return std::move(outline.mesh);
}

}  // namespace geotex
