#pragma once
/// The scans that run before CGAL's OFF, OBJ and STL readers (geometry/detail/cgal_readers.cpp):
/// CGAL's readers answer only true or false, so each file is first read line by line here for
/// the problems that can be named with a line and column (declared counts against the file
/// size, non-finite or malformed numbers, index range, polygon size). No CGAL here.

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "common/detail/text.hpp"
#include "common/errors.hpp"

namespace geotex::detail {

// Context of the scan of one file, for the errors.
struct Scan {
    const std::string& name;

    [[noreturn]] void fail(const std::string& message, long line = 0, long column = 0) const {
        throw ParseError(message, name, line, column);
    }

    // A coordinate as CGAL's readers (istream >> double) will read it; non-finite and
    // overflowing numbers make them fail without a reason, so they are caught here.
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
    std::size_t body_offset = 0;     // first byte after the header
    std::size_t keyword_offset = 0;  // first byte of the keyword
    std::size_t keyword_prefix = 0;  // bytes of its ST, C and N prefixes
    bool textures = false;           // ST prefix
    bool normals = false;            // N prefix
};

/// The header as CGAL reads it: comment lines, a keyword [ST][C][N][4][n]OFF, then either
/// BINARY or the counts (vertices, faces, edges), possibly on later lines.
OffHeader scan_off_header(const Scan& scan, std::string_view data);
/// The declared counts against the file size, before anything is allocated.
void check_off_sizes(const Scan& scan, const OffHeader& h, std::size_t file_size);
/// OFF BINARY: the body's counts and coordinates.
void scan_off_binary_body(const Scan& scan, const OffHeader& h, std::string_view data);
/// ASCII body: numbers, index range, polygon sizes; the line of each face.
std::vector<long> scan_off_body(const Scan& scan, const OffHeader& h, std::string_view data);

// ---- OBJ -----------------------------------------------------------------------------------

struct ObjScan {
    std::vector<long> face_lines;
    bool needs_copy = false;  // tabs or statements CGAL refuses: give CGAL a cleaned copy
};

/// `v` and `f` statements checked, the line of each face; whether CGAL needs a cleaned copy.
ObjScan scan_obj(const Scan& scan, std::string_view data);
/// The copy CGAL reads when scan_obj says so.
std::string clean_obj(std::string_view data);

// ---- STL -----------------------------------------------------------------------------------

bool starts_with_solid(std::string_view data);
/// A little-endian 32-bit unsigned at byte `at` (the caller checks the size).
std::uint32_t le32(std::string_view data, std::size_t at);
/// Binary STL: the n triangles' coordinates.
void scan_binary_stl(const Scan& scan, std::string_view data, std::uint64_t n);
/// ASCII STL: the solid/facet/loop/vertex structure and numbers.
void scan_ascii_stl(const Scan& scan, std::string_view data);

}  // namespace geotex::detail
