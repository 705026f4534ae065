// The scans before CGAL's readers (mesh_scan.hpp): line by line, with lines and columns in
// the errors.

#include "geometry/detail/mesh_scan.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace geotex::detail {
namespace {

constexpr std::uint64_t kMaxInt = static_cast<std::uint64_t>(std::numeric_limits<int>::max());

// Lines of a text, numbered from 1, without their "\n" or "\r\n".
class TextLines {
  public:
    explicit TextLines(std::string_view data) : data_(data) {}

    bool next(std::string_view& line) {
        if (!next_line(data_, pos_, line)) return false;
        ++line_;
        return true;
    }

    long line() const { return line_; }
    std::size_t offset() const { return pos_; }

  private:
    std::string_view data_;
    std::size_t pos_ = 0;
    long line_ = 0;
};

bool starts_with_ci(std::string_view s, std::string_view prefix) {
    if (s.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i) {
        char c = s[i];
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
        if (c != prefix[i]) return false;
    }
    return true;
}

// CGAL doubles the edge count of an OFF header in an int (an estimate of the half-edges), which
// overflows from 2^30 on; geotex does not use the count otherwise.
constexpr std::int64_t kMaxOffEdges = static_cast<std::int64_t>(kMaxInt / 2);

// Big-endian int32 at `at` (the caller checks that 4 bytes are there).
std::int32_t be32_at(std::string_view data, std::size_t at) {
    const auto* b = reinterpret_cast<const unsigned char*>(data.data()) + at;
    return static_cast<std::int32_t>((std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) |
                                     (std::uint32_t{b[2]} << 8) | std::uint32_t{b[3]});
}

bool is_cgal_obj_keyword(std::string_view s) {
    // Statements CGAL's OBJ reader accepts and ignores (besides v, vt, vn, f and comments).
    static const char* const ignored[] = {
        "vp",    "bevel",    "lod",      "ctech",      "c_interp",  "usemap",   "usemtl",
        "stech", "d_interp", "mtllib",   "shadow_obj", "trace_obj", "o",        "g",
        "s",     "p",        "cstype",   "deg",        "step",      "bmat",     "con",
        "curv",  "curv2",    "surf",     "parm",       "trim",      "hole",     "scrv",
        "sp",    "end",      "surf_1",   "q0_1",       "q1_1",      "curv2d_1", "surf_2",
        "q0_2",  "q1_2",     "curv2d_2", "bsp",        "bzp",       "cdc",      "cdp",
        "res"};
    for (const char* k : ignored) {
        if (s == k) return true;
    }
    return false;
}

}  // namespace

void Scan::check_number(const TextToken& t, long line, const std::string& what) const {
    std::string_view s = t.text;
    if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.remove_prefix(1);
    if (starts_with_ci(s, "nan") || starts_with_ci(s, "inf")) {
        fail(what + ": non-finite coordinate '" + printable(t.text) + "'", line, t.column);
    }
    const char* first = t.text.data();
    const char* last = first + t.text.size();
    if (first != last && *first == '+') ++first;
    double value = 0.0;
    const auto res = std::from_chars(first, last, value);
    if (res.ptr != last || (res.ec != std::errc() && res.ec != std::errc::result_out_of_range)) {
        fail(what + ": expected a number, got '" + printable(t.text) + "'", line, t.column);
    }
    if (res.ec == std::errc::result_out_of_range) {
        // Underflow reads as 0 or a subnormal, which istream accepts; overflow it rejects.
        const std::string copy(t.text);
        if (!std::isfinite(std::strtod(copy.c_str(), nullptr))) {
            fail(what + ": coordinate '" + printable(t.text) + "' overflows a double", line,
                 t.column);
        }
    }
}

// ---- OFF -----------------------------------------------------------------------------------

// The header as CGAL reads it: comment lines, a keyword [ST][C][N][4][n]OFF, then either
// BINARY or the counts (vertices, faces, edges), possibly on later lines.
OffHeader scan_off_header(const Scan& scan, std::string_view data) {
    OffHeader h;
    TextLines lines(data);
    std::string_view line;
    std::vector<TextToken> tokens;
    std::size_t next = 0;
    auto next_token = [&](const char* what) -> TextToken {
        while (next >= tokens.size()) {
            if (!lines.next(line)) {
                scan.fail(
                    std::string("end of file in the OFF header, where ") + what + " was expected",
                    lines.line());
            }
            tokens = split_tokens(line, true);
            next = 0;
        }
        return tokens[next++];
    };
    const TextToken keyword = next_token("the keyword OFF");
    std::string_view k = keyword.text;
    h.textures = k.substr(0, 2) == "ST";
    if (h.textures) k.remove_prefix(2);
    if (!k.empty() && k[0] == 'C') k.remove_prefix(1);
    h.normals = !k.empty() && k[0] == 'N';
    if (h.normals) k.remove_prefix(1);
    h.keyword_offset = static_cast<std::size_t>(keyword.text.data() - data.data());
    h.keyword_prefix = keyword.text.size() - k.size();
    if (!k.empty() && k[0] == '4') {
        h.homogeneous = true;
        k.remove_prefix(1);
    }
    bool dimensional = false;
    if (!k.empty() && k[0] == 'n') {
        dimensional = true;
        k.remove_prefix(1);
    }
    if (k != "OFF") {
        scan.fail(
            "not a valid OFF file: expected the keyword OFF (optionally prefixed by ST, C, "
            "N, 4 or n), got '" +
                printable(keyword.text) + "'",
            lines.line(), keyword.column);
    }
    auto count = [&](const char* what) {
        const TextToken t = next_token(what);
        std::int64_t value = 0;
        if (!Scan::parse_int(t.text, value) || value < 0 ||
            static_cast<std::uint64_t>(value) > kMaxInt) {
            scan.fail(std::string("not a valid OFF file: the ") + what +
                          " must be a non-negative integer below 2^31, got '" + printable(t.text) +
                          "'",
                      lines.line(), t.column);
        }
        h.counts_line = lines.line();
        h.counts_column = t.column;
        return value;
    };
    if (next < tokens.size() && tokens[next].text == "BINARY") {
        h.binary = true;
        h.body_offset = lines.offset();
        const std::size_t need = dimensional ? 16 : 12;
        if (data.size() - h.body_offset < need) scan.fail("end of file in the OFF BINARY header");
        auto be32 = [&](std::size_t at) {
            const auto* b = reinterpret_cast<const unsigned char*>(data.data()) + at;
            return static_cast<std::int32_t>((std::uint32_t{b[0]} << 24) |
                                             (std::uint32_t{b[1]} << 16) |
                                             (std::uint32_t{b[2]} << 8) | std::uint32_t{b[3]});
        };
        std::size_t at = h.body_offset;
        if (dimensional) {
            if (be32(at) != 3) scan.fail("only 3-dimensional OFF files are supported");
            at += 4;
        }
        h.num_vertices = be32(at);
        h.num_faces = be32(at + 4);
        if (h.num_vertices < 0 || h.num_faces < 0) {
            scan.fail("not a valid OFF file: negative vertex or face count in the binary header");
        }
        const std::int64_t edges = be32(at + 8);
        if (edges < 0 || edges > kMaxOffEdges) {
            scan.fail("not a valid OFF file: the edge count " + std::to_string(edges) +
                      " in the binary header is outside [0, 2^30) (geotex does not use it: "
                      "write 0)");
        }
        h.body_offset = at + 12;
        return h;
    }
    if (dimensional && count("dimension") != 3) {
        scan.fail("only 3-dimensional OFF files are supported", h.counts_line, h.counts_column);
    }
    h.num_vertices = count("vertex count");
    const long vertex_count_column = h.counts_column;
    h.num_faces = count("face count");
    const std::int64_t edges = count("edge count");
    if (edges > kMaxOffEdges) {
        scan.fail("not a valid OFF file: the edge count " + std::to_string(edges) +
                      " is 2^30 or more (geotex does not use it: write 0)",
                  h.counts_line, h.counts_column);
    }
    // CGAL reads the rest of the line of the counts as the first vertex.
    if (next < tokens.size()) {
        scan.fail("not a valid OFF file: '" + printable(tokens[next].text) +
                      "' after the edge count (the vertices start on the next line)",
                  lines.line(), tokens[next].column);
    }
    h.counts_column = vertex_count_column;
    h.body_offset = lines.offset();
    return h;
}

// The binary body as CGAL reads it: per vertex 3 floats (4 with the 4 prefix), as many again
// for a normal with N and 2 (3) for a texture coordinate with ST (CGAL reads no colour in
// binary); per face an int32 count n and n int32 indices. CGAL sizes each polygon from n
// before it reads the indices, so a count that the file cannot hold is refused here.
void scan_off_binary_body(const Scan& scan, const OffHeader& h, std::string_view data) {
    const std::uint64_t coords = h.homogeneous ? 4 : 3;
    const std::uint64_t vertex_bytes =
        4 * (coords + (h.normals ? coords : 0) + (h.textures ? coords - 1 : 0));
    std::uint64_t at = h.body_offset + static_cast<std::uint64_t>(h.num_vertices) * vertex_bytes;
    for (std::int64_t f = 0; f < h.num_faces; ++f) {
        const std::string where =
            "face " + std::to_string(f) + " (byte " + std::to_string(at) + ")";
        if (at + 4 > data.size()) {
            scan.fail(where + ": end of file after " + std::to_string(f) + " of " +
                      std::to_string(h.num_faces) + " faces");
        }
        const std::int64_t n = be32_at(data, static_cast<std::size_t>(at));
        at += 4;
        if (n < 3) {
            scan.fail(where + ": polygon with " + std::to_string(n) +
                      " vertices (at least 3 needed)");
        }
        if (static_cast<std::uint64_t>(n) > (data.size() - at) / 4) {
            scan.fail(where + ": " + std::to_string(n) + " vertex indices, but only " +
                      std::to_string(data.size() - at) + " bytes remain");
        }
        for (std::int64_t j = 0; j < n; ++j, at += 4) {
            const std::int64_t index = be32_at(data, static_cast<std::size_t>(at));
            if (index < 0 || index >= h.num_vertices) {
                scan.fail(where + ": vertex index " + std::to_string(index) +
                          " out of range (the file has " + std::to_string(h.num_vertices) +
                          " vertices)");
            }
        }
    }
}

// Declared counts against the remaining bytes, before CGAL resizes its containers to them.
void check_off_sizes(const Scan& scan, const OffHeader& h, std::size_t file_size) {
    const std::uint64_t available = file_size - h.body_offset;
    // Binary: 3 floats per vertex, 4 int32 per face. ASCII: at least 2 bytes per line, a
    // bound loose enough that a short file reaches the missing line and the error names it.
    const std::uint64_t per_vertex = h.binary ? 12 : 2;
    const std::uint64_t per_face = h.binary ? 16 : 2;
    const std::uint64_t need = static_cast<std::uint64_t>(h.num_vertices) * per_vertex +
                               static_cast<std::uint64_t>(h.num_faces) * per_face;
    if (need > available + (h.binary ? 0 : 1)) {
        scan.fail("not a valid OFF file: the header declares " + std::to_string(h.num_vertices) +
                      " vertices and " + std::to_string(h.num_faces) +
                      " faces, which need at least " + std::to_string(need) + " bytes, but only " +
                      std::to_string(available) + " bytes follow",
                  h.counts_line, h.counts_column);
    }
    if (h.num_faces == 0) scan.fail("the file has no faces", h.counts_line);
}

// The ASCII body, line by line as CGAL reads it (one vertex or face per line, '#' starts a
// comment). Returns the line of each face.
std::vector<long> scan_off_body(const Scan& scan, const OffHeader& h, std::string_view data) {
    TextLines lines(data.substr(h.body_offset));
    const long line_base = h.counts_line;  // lines of the body are counted from here
    std::vector<long> face_lines;
    // Counts are not trusted until the lines are there: reserve what the text can hold.
    face_lines.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(
        static_cast<std::uint64_t>(h.num_faces), (data.size() - h.body_offset) / 8 + 1)));
    std::string_view line;
    std::vector<TextToken> tokens;
    const std::size_t coords = h.homogeneous ? 4 : 3;
    auto next_record = [&](const std::string& what, std::int64_t i, std::int64_t n) {
        for (;;) {
            if (!lines.next(line)) {
                scan.fail("end of file after " + std::to_string(i) + " of " + std::to_string(n) +
                              " " + what,
                          line_base + lines.line() + 1);
            }
            tokens = split_tokens(line, true);
            if (!tokens.empty()) return line_base + lines.line();
        }
    };
    for (std::int64_t v = 0; v < h.num_vertices; ++v) {
        const long ln = next_record("vertices", v, h.num_vertices);
        const std::string where = "vertex " + std::to_string(v);
        if (tokens.size() < coords) {
            scan.fail(where + ": expected " + std::to_string(coords) + " coordinates, found " +
                          std::to_string(tokens.size()),
                      ln, tokens.back().column);
        }
        for (std::size_t k = 0; k < tokens.size(); ++k) scan.check_number(tokens[k], ln, where);
        if (h.homogeneous && std::strtod(std::string(tokens[3].text).c_str(), nullptr) == 0.0) {
            scan.fail(where + ": homogeneous coordinate w = 0", ln, tokens[3].column);
        }
    }
    for (std::int64_t f = 0; f < h.num_faces; ++f) {
        const long ln = next_record("faces", f, h.num_faces);
        face_lines.push_back(ln);
        const std::string where = "face " + std::to_string(f);
        std::int64_t n = 0;
        if (!Scan::parse_int(tokens[0].text, n) || n < 0) {
            scan.fail(where + ": expected a vertex count, got '" + printable(tokens[0].text) + "'",
                      ln, tokens[0].column);
        }
        if (n < 3) {
            scan.fail(
                where + ": polygon with " + std::to_string(n) + " vertices (at least 3 needed)", ln,
                tokens[0].column);
        }
        if (static_cast<std::uint64_t>(n) >= tokens.size()) {
            scan.fail(where + ": expected " + std::to_string(n) + " vertex indices, found " +
                          std::to_string(tokens.size() - 1),
                      ln, tokens.back().column);
        }
        for (std::int64_t j = 1; j <= n; ++j) {
            const TextToken& t = tokens[static_cast<std::size_t>(j)];
            std::int64_t index = 0;
            if (!Scan::parse_int(t.text, index)) {
                scan.fail(where + ": expected a vertex index, got '" + printable(t.text) + "'", ln,
                          t.column);
            }
            if (index < 0) {
                scan.fail(where + ": negative vertex index " + std::to_string(index), ln, t.column);
            }
            if (index >= h.num_vertices) {
                scan.fail(where + ": vertex index " + std::to_string(index) +
                              " out of range (the file has " + std::to_string(h.num_vertices) +
                              " vertices)",
                          ln, t.column);
            }
        }
        // Numbers after the indices are a colour, which CGAL reads and we drop.
        for (std::size_t k = static_cast<std::size_t>(n) + 1; k < tokens.size(); ++k) {
            scan.check_number(tokens[k], ln, where);
        }
    }
    // More records than declared: the counts are wrong, and CGAL would drop the rest.
    while (lines.next(line)) {
        tokens = split_tokens(line, true);
        if (tokens.empty()) continue;
        scan.fail("'" + printable(tokens[0].text) + "' after the last declared face: the file " +
                      "holds more than its header's counts (" + std::to_string(h.num_vertices) +
                      " vertices, " + std::to_string(h.num_faces) + " faces) describe",
                  line_base + lines.line(), tokens[0].column);
    }
    return face_lines;
}

// ---- OBJ -----------------------------------------------------------------------------------

ObjScan scan_obj(const Scan& scan, std::string_view data) {
    ObjScan result;
    TextLines lines(data);
    std::string_view line;
    std::int64_t num_vertices = 0;
    struct Forward {
        std::int64_t index;
        long line;
        long column;
    };
    std::vector<Forward> forward;  // indices past the vertices read so far (allowed by CGAL)
    while (lines.next(line)) {
        const long ln = lines.line();
        if (line.find('\t') != std::string_view::npos) result.needs_copy = true;
        const std::vector<TextToken> tokens = split_tokens(line, true);
        if (tokens.empty()) continue;
        const std::string_view keyword = tokens[0].text;
        if (keyword == "v") {
            const std::string where = "vertex " + std::to_string(num_vertices);
            if (tokens.size() < 4) {
                scan.fail(where + ": expected 3 coordinates after 'v', found " +
                              std::to_string(tokens.size() - 1),
                          ln, tokens.back().column);
            }
            for (std::size_t k = 1; k < tokens.size(); ++k) scan.check_number(tokens[k], ln, where);
            ++num_vertices;
        } else if (keyword == "f") {
            const std::string where = "face " + std::to_string(result.face_lines.size());
            if (tokens.size() < 4) {
                scan.fail(where + ": polygon with " + std::to_string(tokens.size() - 1) +
                              " vertices (at least 3 needed)",
                          ln, tokens[0].column);
            }
            for (std::size_t k = 1; k < tokens.size(); ++k) {
                const TextToken& t = tokens[k];
                // v, v/vt, v//vn or v/vt/vn: the vertex index is the part before '/'.
                const std::string_view v = t.text.substr(0, t.text.find('/'));
                std::int64_t index = 0;
                if (!Scan::parse_int(v, index) || v[0] == '+') {
                    scan.fail(where +
                                  ": expected a vertex index (v, v/vt, v//vn or v/vt/vn), "
                                  "got '" +
                                  printable(t.text) + "'",
                              ln, t.column);
                }
                if (index == 0) {
                    scan.fail(where + ": vertex index 0 is invalid (OBJ counts from 1)", ln,
                              t.column);
                }
                if (index < -num_vertices) {  // not -index: it overflows for INT64_MIN
                    scan.fail(where + ": relative vertex index " + std::to_string(index) +
                                  " refers before the first vertex (" +
                                  std::to_string(num_vertices) + " vertices so far)",
                              ln, t.column);
                }
                if (index > num_vertices) forward.push_back({index, ln, t.column});
            }
            result.face_lines.push_back(ln);
        } else if (keyword == "l") {
            result.needs_copy = true;  // polylines are valid OBJ but no surface; CGAL refuses them
        } else if (keyword == "vt" || keyword == "vn" || keyword[0] == '#' ||
                   is_cgal_obj_keyword(keyword)) {
            continue;
        } else {
            scan.fail("unknown OBJ statement '" + printable(keyword) + "'", ln, tokens[0].column);
        }
    }
    for (const Forward& f : forward) {
        if (f.index > num_vertices) {
            scan.fail("vertex index " + std::to_string(f.index) + " out of range (the file has " +
                          std::to_string(num_vertices) + " vertices)",
                      f.line, f.column);
        }
    }
    if (num_vertices == 0) scan.fail("the file has no vertices");
    if (result.face_lines.empty()) scan.fail("the file has no faces");
    return result;
}

// Tabs become spaces (CGAL skips from an index to the next space) and polyline statements
// become blank lines, which keeps the line count.
std::string clean_obj(std::string_view data) {
    std::string out(data);
    std::size_t start = 0;
    while (start < out.size()) {
        std::size_t end = out.find('\n', start);
        if (end == std::string::npos) end = out.size();
        for (std::size_t i = start; i < end; ++i) {
            if (out[i] == '\t') out[i] = ' ';
        }
        std::size_t first = start;
        while (first < end && is_space(out[first])) ++first;
        if (first < end && out[first] == 'l' && (first + 1 == end || is_space(out[first + 1]))) {
            for (std::size_t i = start; i < end; ++i) out[i] = ' ';
        }
        start = end + 1;
    }
    return out;
}

// ---- STL -----------------------------------------------------------------------------------

bool starts_with_solid(std::string_view data) {
    std::size_t i = 0;
    while (i < data.size() && is_space(data[i])) ++i;
    return data.substr(i, 5) == "solid" && (i + 5 == data.size() || is_space(data[i + 5]));
}

std::uint32_t le32(std::string_view data, std::size_t at) {
    const auto* b = reinterpret_cast<const unsigned char*>(data.data()) + at;
    return std::uint32_t{b[0]} | (std::uint32_t{b[1]} << 8) | (std::uint32_t{b[2]} << 16) |
           (std::uint32_t{b[3]} << 24);
}

void scan_binary_stl(const Scan& scan, std::string_view data, std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i) {
        const std::size_t record = 84 + 50 * static_cast<std::size_t>(i);
        // 3 floats of normal (ignored), then 3 vertices of 3 floats.
        for (std::size_t k = 3; k < 12; ++k) {
            const std::uint32_t bits = le32(data, record + 4 * k);
            float value = 0.0F;
            std::memcpy(&value, &bits, 4);
            if (!std::isfinite(value)) {
                scan.fail("triangle " + std::to_string(i) + " of " + std::to_string(n) + " (byte " +
                          std::to_string(record + 4 * k) + "): non-finite vertex coordinate");
            }
        }
    }
}

// ASCII STL as CGAL reads it: facets of exactly three `vertex x y z` between `facet` and
// `endfacet`, inside `solid` ... `endsolid`.
void scan_ascii_stl(const Scan& scan, std::string_view data) {
    TextLines lines(data);
    std::string_view line;
    bool in_facet = false;
    bool solid_closed = false;
    long facet_line = 0;
    int corners = 0;
    std::int64_t facets = 0;
    while (lines.next(line)) {
        const long ln = lines.line();
        const std::vector<TextToken> tokens = split_tokens(line, false);
        if (tokens.empty()) continue;
        const std::string_view keyword = tokens[0].text;
        const std::string where = "facet " + std::to_string(facets);
        if (keyword == "facet") {
            if (in_facet) scan.fail(where + ": 'facet' before 'endfacet'", ln, tokens[0].column);
            in_facet = true;
            facet_line = ln;
            corners = 0;
        } else if (keyword == "vertex") {
            if (!in_facet) scan.fail("'vertex' outside a facet", ln, tokens[0].column);
            if (++corners > 3) {
                scan.fail(where + ": more than 3 vertices (STL facets are triangles)", ln,
                          tokens[0].column);
            }
            if (tokens.size() < 4) {
                scan.fail(where + ": expected 3 coordinates after 'vertex', found " +
                              std::to_string(tokens.size() - 1),
                          ln, tokens.back().column);
            }
            for (std::size_t k = 1; k < 4; ++k) scan.check_number(tokens[k], ln, where);
        } else if (keyword == "endfacet") {
            if (!in_facet) scan.fail("'endfacet' without 'facet'", ln, tokens[0].column);
            if (corners != 3) {
                scan.fail(
                    where + ": " + std::to_string(corners) + " vertices (STL facets are triangles)",
                    facet_line, 0);
            }
            in_facet = false;
            ++facets;
        } else if (keyword == "endsolid") {
            solid_closed = true;
        }
    }
    if (in_facet) {
        scan.fail("end of file inside facet " + std::to_string(facets) + " (begun on line " +
                      std::to_string(facet_line) + ")",
                  lines.line() + 1);
    }
    if (!solid_closed) scan.fail("end of file before 'endsolid'", lines.line() + 1);
    if (facets == 0) scan.fail("the file has no faces");
}

}  // namespace geotex::detail
