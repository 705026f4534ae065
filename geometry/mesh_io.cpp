#include "geometry/mesh_io.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <ostream>
#include <system_error>

#ifdef __linux__
#include <sys/mman.h>
#endif

#include "common/errors.hpp"
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

void check_write_input(const Mesh& mesh, const std::vector<FaceAttribute>& face_attributes,
                       const PlyWriteOptions& options) {
    const int nv = mesh.num_vertices();
    for (int v = 0; v < nv; ++v) {
        if (!mesh.positions[v].allFinite()) {
            throw InvalidInput("write_ply: vertex " + std::to_string(v) +
                               " has a non-finite coordinate; PLY readers reject it");
        }
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
        for (int k = 0; k < 3; ++k) {
            const int index = mesh.faces[f][k];
            if (index < 0 || index >= nv) {
                throw InvalidInput("write_ply: face " + std::to_string(f) + " references vertex " +
                                   std::to_string(index) + ", but the mesh has " +
                                   std::to_string(nv) + " vertices");
            }
        }
    }
    for (const FaceAttribute& a : face_attributes) {
        if (!valid_ply_name(a.name) || a.name == "vertex_indices" || a.name == "vertex_index") {
            throw InvalidInput("write_ply: face attribute name '" + a.name +
                               "' is not a valid PLY property name (non-empty, printable, no "
                               "spaces, not vertex_indices)");
        }
        const std::vector<int>& values = a.source();
        if (values.size() != mesh.faces.size()) {
            throw InvalidInput("write_ply: face attribute '" + a.name + "' has " +
                               std::to_string(values.size()) + " values, but the mesh has " +
                               std::to_string(mesh.faces.size()) + " faces");
        }
        if (a.table.empty() && a.type == PlyScalarType::Int32) continue;  // any int is written
        for (std::size_t f = 0; f < values.size(); ++f) {
            const long row = static_cast<long>(values[f]) - a.table_first;
            if (!a.table.empty() && (row < 0 || row >= static_cast<long>(a.table.size()))) {
                throw InvalidInput("write_ply: face attribute '" + a.name + "': face " +
                                   std::to_string(f) + " has value " + std::to_string(values[f]) +
                                   ", outside its table");
            }
            const int written = written_value(a, values, f);
            if (a.type == PlyScalarType::UInt8 && (written < 0 || written > 255)) {
                throw InvalidInput("write_ply: face attribute '" + a.name +
                                   "' is uchar, but face " + std::to_string(f) + " has value " +
                                   std::to_string(written) + " (outside 0..255)");
            }
        }
    }
    for (const std::string& c : options.comments) {
        if (c.find_first_of("\r\n") != std::string::npos) {
            throw InvalidInput("write_ply: a header comment contains a line break");
        }
    }
}

// The bytes of a file being read: not zeroed first (the read overwrites them all), and on
// Linux in 2 MB pages when large. Zeroing, then the page faults of 4 kB pages (one per 4 kB
// on first touch, slow in virtual machines) took more time than the parse of an ASCII mesh.
class FileBuffer {
  public:
    explicit FileBuffer(std::size_t size) {
        constexpr std::size_t kHuge = std::size_t{2} << 20;
        if (size >= kHuge) {
            const std::size_t rounded = (size + kHuge - 1) / kHuge * kHuge;
            data_ = static_cast<char*>(std::aligned_alloc(kHuge, rounded));
#ifdef __linux__
            if (data_ != nullptr) madvise(data_, rounded, MADV_HUGEPAGE);  // a hint only
#endif
        } else {
            data_ = static_cast<char*>(std::malloc(size + 1));
        }
        if (data_ == nullptr) throw std::bad_alloc();
    }
    ~FileBuffer() { std::free(data_); }
    FileBuffer(const FileBuffer&) = delete;
    FileBuffer& operator=(const FileBuffer&) = delete;

    char* get() const { return data_; }

  private:
    char* data_ = nullptr;
};

}  // namespace

MeshFile read_mesh_memory(std::string_view data, const std::string& name) {
    const MeshFormat format = format_of(name);
    // Text editors on Windows start a UTF-8 file with a byte order mark, which they do not
    // show: OBJ and OFF are text, so it is skipped (line 1 columns then count from after
    // it, as the editor shows them). PLY and STL start with a signature and keep theirs.
    if ((format == MeshFormat::Obj || format == MeshFormat::Off) &&
        data.substr(0, 3) == "\xEF\xBB\xBF")
        data.remove_prefix(3);
    switch (format) {
        case MeshFormat::Ply:
            return detail::read_ply(data, name);
        case MeshFormat::Off:
            return detail::read_off(data, name);
        case MeshFormat::Obj:
            return detail::read_obj(data, name);
        case MeshFormat::Stl:
            return detail::read_stl(data, name);
    }
    return {};
}

MeshFile read_mesh_file(const std::string& path) {
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
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw IoError(std::string("cannot open mesh file: ") + std::strerror(errno), path);
    }
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    if (size < 0 || !in) {
        throw IoError("cannot read mesh file (not a regular file?)", path);
    }
    FileBuffer data(static_cast<std::size_t>(size));
    in.read(data.get(), size);
    if (in.gcount() != size) {
        throw IoError(std::string("cannot read mesh file: ") + std::strerror(errno), path);
    }
    return read_mesh_memory(std::string_view(data.get(), static_cast<std::size_t>(size)), path);
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

void write_ply(std::ostream& out, const Mesh& mesh,
               const std::vector<FaceAttribute>& face_attributes, const PlyWriteOptions& options) {
    check_write_input(mesh, face_attributes, options);

    bool as_float = true;
    for (const Eigen::Vector3d& p : mesh.positions) {
        as_float = as_float && fits_float_exactly(p.x()) && fits_float_exactly(p.y()) &&
                   fits_float_exactly(p.z());
    }
    const char* coord_type = as_float ? "float" : "double";

    std::string buf;
    buf += "ply\n";
    buf += options.binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n";
    for (const std::string& c : options.comments) buf += "comment " + c + "\n";
    buf += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
    for (const char* axis : {"x", "y", "z"}) {
        buf += std::string("property ") + coord_type + " " + axis + "\n";
    }
    buf += "element face " + std::to_string(mesh.faces.size()) + "\n";
    buf += "property list uchar int vertex_indices\n";
    for (const FaceAttribute& a : face_attributes) {
        buf += std::string("property ") + (a.type == PlyScalarType::Int32 ? "int" : "uchar") + " " +
               a.name + "\n";
    }
    buf += "end_header\n";

    if (options.binary) {
        buf.reserve(kWriteChunk + 4096);
        for (const Eigen::Vector3d& p : mesh.positions) {
            flush_full(out, buf);
            for (int k = 0; k < 3; ++k) {
                if (as_float) {
                    const float f = static_cast<float>(p[k]);
                    std::uint32_t bits = 0;
                    std::memcpy(&bits, &f, 4);
                    append_le32(buf, bits);
                } else {
                    std::uint64_t bits = 0;
                    std::memcpy(&bits, &p[k], 8);
                    append_le64(buf, bits);
                }
            }
        }
        for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
            flush_full(out, buf);
            buf += static_cast<char>(3);
            for (int k = 0; k < 3; ++k) {
                append_le32(buf, static_cast<std::uint32_t>(mesh.faces[f][k]));
            }
            for (const FaceAttribute& a : face_attributes) {
                const int value = written_value(a, a.source(), f);
                if (a.type == PlyScalarType::Int32) {
                    append_le32(buf, static_cast<std::uint32_t>(value));
                } else {
                    buf += static_cast<char>(static_cast<unsigned char>(value));
                }
            }
        }
    } else {
        // Shortest text that reads back to the same float or double.
        for (const Eigen::Vector3d& p : mesh.positions) {
            flush_full(out, buf);
            for (int k = 0; k < 3; ++k) {
                if (k > 0) buf += ' ';
                if (as_float) {
                    append_text(buf, static_cast<float>(p[k]));
                } else {
                    append_text(buf, p[k]);
                }
            }
            buf += '\n';
        }
        for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
            flush_full(out, buf);
            buf += '3';
            for (int k = 0; k < 3; ++k) {
                buf += ' ';
                append_text(buf, mesh.faces[f][k]);
            }
            for (const FaceAttribute& a : face_attributes) {
                buf += ' ';
                append_text(buf, written_value(a, a.source(), f));
            }
            buf += '\n';
        }
    }

    out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    if (!out) throw IoError("write_ply: writing the PLY data failed");
}

}  // namespace geotex
