#include "geometry/mesh_io.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <system_error>

#include "common/errors.hpp"
#include "geometry/detail/mapped_file.hpp"
#include "geometry/detail/ply.hpp"
#include "geometry/detail/text_mesh_readers.hpp"

namespace geotex {
namespace {

// Lower-case extension of the file name part of `path`, with its dot ("" if none).
std::string extension_of(const std::string& path) {
    const std::size_t slash = path.find_last_of("/\\");
    const std::size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot);
    for (char& c : ext) {
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    return ext;
}

enum class MeshFormat { Ply, Off, Obj, Stl };

MeshFormat format_of(const std::string& path) {
    const std::string ext = extension_of(path);
    if (ext == ".ply") return MeshFormat::Ply;
    if (ext == ".off") return MeshFormat::Off;
    if (ext == ".obj") return MeshFormat::Obj;
    if (ext == ".stl") return MeshFormat::Stl;
    throw InvalidInput("unknown mesh extension '" + ext + "' (expected .ply, .off, .obj or .stl)",
                       path);
}

void append_le32(std::string& buf, std::uint32_t v) {
    const char bytes[4] = {static_cast<char>(v & 0xFF), static_cast<char>((v >> 8) & 0xFF),
                           static_cast<char>((v >> 16) & 0xFF),
                           static_cast<char>((v >> 24) & 0xFF)};
    buf.append(bytes, 4);
}

void append_le64(std::string& buf, std::uint64_t v) {
    append_le32(buf, static_cast<std::uint32_t>(v & 0xFFFFFFFFU));
    append_le32(buf, static_cast<std::uint32_t>(v >> 32));
}

template <typename T>
void append_text(std::string& buf, T value) {
    char tmp[64];
    const auto res = std::to_chars(tmp, tmp + sizeof(tmp), value);
    buf.append(tmp, res.ptr);
}

bool fits_float_exactly(double v) {
    return std::abs(v) <= static_cast<double>(std::numeric_limits<float>::max()) &&
           static_cast<double>(static_cast<float>(v)) == v;
}

bool valid_ply_name(const std::string& s) {
    if (s.empty()) return false;
    for (char c : s) {
        if (static_cast<unsigned char>(c) <= 32 || static_cast<unsigned char>(c) >= 127) {
            return false;
        }
    }
    return true;
}

// The value written for face f of attribute a, whose values are `values` (a.source()).
int written_value(const FaceAttribute& a, const std::vector<int>& values, std::size_t f) {
    return a.table.empty()
               ? values[f]
               : a.table[static_cast<std::size_t>(static_cast<long>(values[f]) - a.table_first)];
}

// The header's names and comments, before a byte is written.
void check_header(const std::vector<FaceAttribute>& face_attributes,
                  const PlyWriteOptions& options) {
    for (const FaceAttribute& a : face_attributes) {
        if (!valid_ply_name(a.name) || a.name == "vertex_indices" || a.name == "vertex_index") {
            throw InvalidInput("write_ply: face attribute name '" + a.name +
                               "' is not a valid PLY property name (non-empty, printable, no "
                               "spaces, not vertex_indices)");
        }
    }
    for (const std::string& c : options.comments) {
        if (c.find_first_of("\r\n") != std::string::npos) {
            throw InvalidInput("write_ply: a header comment contains a line break");
        }
    }
}

// Vertices first + 0, 1, ... are finite.
void check_vertices(PositionSpan positions, std::size_t first) {
    for (std::size_t v = 0; v < positions.size(); ++v) {
        if (!positions[v].allFinite()) {
            throw InvalidInput("write_ply: vertex " + std::to_string(first + v) +
                               " has a non-finite coordinate; PLY readers reject it");
        }
    }
}

// Faces first + 0, 1, ... name vertices below num_vertices, and their attributes' values, one
// per face of the block, fit their tables and types. `whole`: the block is the whole mesh.
void check_faces(const std::vector<std::array<int, 3>>& faces, std::size_t first, bool whole,
                 std::size_t num_vertices, const std::vector<FaceAttribute>& face_attributes) {
    for (std::size_t f = 0; f < faces.size(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int index = faces[f][k];
            if (index < 0 || static_cast<std::size_t>(index) >= num_vertices) {
                throw InvalidInput("write_ply: face " + std::to_string(first + f) +
                                   " references vertex " + std::to_string(index) +
                                   ", but the mesh has " + std::to_string(num_vertices) +
                                   " vertices");
            }
        }
    }
    for (const FaceAttribute& a : face_attributes) {
        const std::vector<int>& values = a.source();
        if (values.size() != faces.size()) {
            throw InvalidInput("write_ply: face attribute '" + a.name + "' has " +
                               std::to_string(values.size()) + " values, but the " +
                               (whole ? "mesh" : "block of faces") + " has " +
                               std::to_string(faces.size()) + " faces");
        }
        if (a.table.empty() && a.type == PlyScalarType::Int32) continue;  // any int is written
        for (std::size_t f = 0; f < values.size(); ++f) {
            const long row = static_cast<long>(values[f]) - a.table_first;
            if (!a.table.empty() && (row < 0 || row >= static_cast<long>(a.table.size()))) {
                throw InvalidInput("write_ply: face attribute '" + a.name + "': face " +
                                   std::to_string(first + f) + " has value " +
                                   std::to_string(values[f]) + ", outside its table");
            }
            const int written = written_value(a, values, f);
            if (a.type == PlyScalarType::UInt8 && (written < 0 || written > 255)) {
                throw InvalidInput("write_ply: face attribute '" + a.name +
                                   "' is uchar, but face " + std::to_string(first + f) +
                                   " has value " + std::to_string(written) + " (outside 0..255)");
            }
        }
    }
}

}  // namespace

MeshFile read_mesh_memory(std::string_view data, const std::string& name, const PolygonSink& sink) {
    const MeshFormat format = format_of(name);
    // Text editors on Windows start a UTF-8 file with a byte order mark, which they do not
    // show: OBJ and OFF are text, so it is skipped (line 1 columns then count from after
    // it, as the editor shows them). PLY and STL start with a signature and keep theirs.
    if ((format == MeshFormat::Obj || format == MeshFormat::Off) &&
        data.substr(0, 3) == "\xEF\xBB\xBF")
        data.remove_prefix(3);
    switch (format) {
        case MeshFormat::Ply:
            return detail::read_ply(data, name, sink);
        case MeshFormat::Off:
            return detail::read_off(data, name, sink);
        case MeshFormat::Obj:
            return detail::read_obj(data, name, sink);
        case MeshFormat::Stl:
            return detail::read_stl(data, name, sink);
    }
    return {};
}

MeshFile read_mesh_file(const std::string& path, const PolygonSink& sink) {
    format_of(path);  // an unknown extension fails before the file is touched
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (std::filesystem::is_directory(status)) {
        throw IoError("cannot read mesh file: it is a directory", path);
    }
    // A pipe would block the open until a writer comes, a device such as /dev/zero never
    // ends: a mesh must be a regular file (a missing one gets the open's own message below).
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
        throw IoError(std::string("cannot read mesh file: it is ") +
                          (std::filesystem::is_fifo(status) ? "a pipe (FIFO)"
                           : std::filesystem::is_character_file(status) ||
                                   std::filesystem::is_block_file(status)
                               ? "a device"
                               : "a socket or other special file") +
                          ", not a regular file",
                      path);
    }
    // Mapped, its pages given back behind the reader (detail/read_window.hpp).
    detail::MappedFile file(path);
    const std::string_view bytes = file.bytes();
    // What a reader made of a file that could not be read whole is not the file, nor is its
    // error: the pages it could not read were zeros.
    const auto check_read = [&] {
        if (const std::optional<std::size_t> at = file.unreadable_from())
            throw IoError("cannot read mesh file past byte " + std::to_string(*at) +
                              " (was it cut short while it was read, or is the disk failing?)",
                          path);
    };
    MeshFile out;
    try {
        out = read_mesh_memory(bytes, path, sink);
    } catch (...) {
        check_read();
        throw;
    }
    check_read();
    return out;
}

namespace {

// The PLY text is made in a buffer of about this size and written each time it fills: a whole
// file in memory would be the largest buffer of a run on a large scan (30 bytes a face).
constexpr std::size_t kWriteChunk = std::size_t{1} << 20;

void flush_full(std::ostream& out, std::string& buf) {
    if (buf.size() < kWriteChunk) return;
    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    buf.clear();
}

}  // namespace

bool ply_fits_float(PositionSpan positions) {
    for (const Eigen::Vector3d& p : positions)
        if (!fits_float_exactly(p.x()) || !fits_float_exactly(p.y()) || !fits_float_exactly(p.z()))
            return false;
    return true;
}

PlyWriter::PlyWriter(std::ostream& out, std::size_t num_vertices, std::size_t num_faces,
                     bool float_coordinates, const std::vector<FaceAttribute>& face_attributes,
                     const PlyWriteOptions& options)
    : out_(out),
      num_vertices_(num_vertices),
      num_faces_(num_faces),
      as_float_(float_coordinates),
      binary_(options.binary) {
    check_header(face_attributes, options);
    const char* coord_type = as_float_ ? "float" : "double";
    buf_ += "ply\n";
    buf_ += binary_ ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n";
    for (const std::string& c : options.comments) buf_ += "comment " + c + "\n";
    buf_ += "element vertex " + std::to_string(num_vertices) + "\n";
    for (const char* axis : {"x", "y", "z"}) {
        buf_ += std::string("property ") + coord_type + " " + axis + "\n";
    }
    buf_ += "element face " + std::to_string(num_faces) + "\n";
    buf_ += "property list uchar int vertex_indices\n";
    for (const FaceAttribute& a : face_attributes) {
        buf_ += std::string("property ") + (a.type == PlyScalarType::Int32 ? "int" : "uchar") +
                " " + a.name + "\n";
        attribute_types_.push_back(a.type);
    }
    buf_ += "end_header\n";
    if (binary_) buf_.reserve(kWriteChunk + 4096);
}

void PlyWriter::vertices(PositionSpan block) {
    if (block.size() > num_vertices_ - vertices_done_)
        throw std::logic_error("PlyWriter: more vertices than the header gives");
    check_vertices(block, vertices_done_);
    for (const Eigen::Vector3d& p : block) {
        flush_full(out_, buf_);
        for (int k = 0; k < 3; ++k) {
            if (binary_ && as_float_) {
                const float f = static_cast<float>(p[k]);
                std::uint32_t bits = 0;
                std::memcpy(&bits, &f, 4);
                append_le32(buf_, bits);
            } else if (binary_) {
                std::uint64_t bits = 0;
                std::memcpy(&bits, &p[k], 8);
                append_le64(buf_, bits);
            } else {
                // Shortest text that reads back to the same float or double.
                if (k > 0) buf_ += ' ';
                if (as_float_) {
                    append_text(buf_, static_cast<float>(p[k]));
                } else {
                    append_text(buf_, p[k]);
                }
            }
        }
        if (!binary_) buf_ += '\n';
    }
    vertices_done_ += block.size();
}

void PlyWriter::faces(const std::vector<std::array<int, 3>>& block,
                      const std::vector<FaceAttribute>& face_attributes) {
    if (vertices_done_ != num_vertices_)
        throw std::logic_error("PlyWriter: faces before every vertex is written");
    if (block.size() > num_faces_ - faces_done_)
        throw std::logic_error("PlyWriter: more faces than the header gives");
    if (face_attributes.size() != attribute_types_.size())
        throw std::logic_error("PlyWriter: a block with other attributes than the header's");
    for (std::size_t i = 0; i < face_attributes.size(); ++i)
        if (face_attributes[i].type != attribute_types_[i])
            throw std::logic_error("PlyWriter: a block with other attributes than the header's");
    check_faces(block, faces_done_, block.size() == num_faces_, num_vertices_, face_attributes);
    for (std::size_t f = 0; f < block.size(); ++f) {
        flush_full(out_, buf_);
        if (binary_) {
            buf_ += static_cast<char>(3);
            for (int k = 0; k < 3; ++k) append_le32(buf_, static_cast<std::uint32_t>(block[f][k]));
            for (const FaceAttribute& a : face_attributes) {
                const int value = written_value(a, a.source(), f);
                if (a.type == PlyScalarType::Int32) {
                    append_le32(buf_, static_cast<std::uint32_t>(value));
                } else {
                    buf_ += static_cast<char>(static_cast<unsigned char>(value));
                }
            }
        } else {
            buf_ += '3';
            for (int k = 0; k < 3; ++k) {
                buf_ += ' ';
                append_text(buf_, block[f][k]);
            }
            for (const FaceAttribute& a : face_attributes) {
                buf_ += ' ';
                append_text(buf_, written_value(a, a.source(), f));
            }
            buf_ += '\n';
        }
    }
    faces_done_ += block.size();
}

void PlyWriter::finish() {
    if (vertices_done_ != num_vertices_ || faces_done_ != num_faces_)
        throw std::logic_error("PlyWriter: fewer vertices or faces than the header gives");
    out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
    if (!out_) throw IoError("write_ply: writing the PLY data failed");
}

void write_ply(std::ostream& out, const Mesh& mesh,
               const std::vector<FaceAttribute>& face_attributes, const PlyWriteOptions& options) {
    PlyWriter ply(out, mesh.positions.size(), mesh.faces.size(), ply_fits_float(mesh.positions),
                  face_attributes, options);
    ply.vertices(mesh.positions);
    ply.faces(mesh.faces, face_attributes);
    ply.finish();
}

}  // namespace geotex
