#pragma once
/// Parts of the OFF, OBJ and STL readers (geometry/detail/obj_reader.cpp, off_reader.cpp,
/// stl_reader.cpp): the error context, the message for a token that is not a usable number, the OFF
/// header with its counts checked against the file size, and the STL signature.

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "common/detail/text.hpp"
#include "common/errors.hpp"

namespace geotex::detail {

/// The largest index or count the readers accept: meshes are indexed by int.
constexpr std::uint64_t kMaxInt = static_cast<std::uint64_t>(std::numeric_limits<int>::max());

// Context of the scan of one file, for the errors.
struct Scan {
    const std::string& name;

    [[noreturn]] void fail(const std::string& message, long line = 0, long column = 0) const {
        throw ParseError(message, name, line, column);
    }

    // Throws the message for a token that is not a finite number (not a number, nan or inf,
    // overflow); returns for a valid number, including one so small that it reads as 0 or a
    // subnormal (as istream >> double reads it).
    void check_number(const TextToken& t, long line, const std::string& what) const;

    // An integer token that must be all of `t`; false if it is not one.
    static bool parse_int(std::string_view t, std::int64_t& value) {
        const char* first = t.data();
        const char* last = first + t.size();
        if (first != last && *first == '+') ++first;
        const auto res = std::from_chars(first, last, value);
        return res.ec == std::errc() && res.ptr == last;
    }
};

// ---- OFF -----------------------------------------------------------------------------------

struct OffHeader {
    bool binary = false;
    bool homogeneous = false;
    std::int64_t num_vertices = 0;
    std::int64_t num_faces = 0;
    long counts_line = 0;
    long counts_column = 0;
    std::size_t body_offset = 0;  // first byte after the header
    bool textures = false;        // ST prefix
    bool normals = false;         // N prefix
};

/// The header as CGAL reads it: comment lines, a keyword [ST][C][N][4][n]OFF, then either
/// BINARY or the counts (vertices, faces, edges), possibly on later lines.
OffHeader scan_off_header(const Scan& scan, std::string_view data);
/// The declared counts against the file size, before anything is allocated.
void check_off_sizes(const Scan& scan, const OffHeader& h, std::size_t file_size);

// ---- STL -----------------------------------------------------------------------------------

bool starts_with_solid(std::string_view data);
/// A little-endian 32-bit unsigned at byte `at` (the caller checks the size).
std::uint32_t le32(std::string_view data, std::size_t at);

}  // namespace geotex::detail
