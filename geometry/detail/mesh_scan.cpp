// The OFF header and the number checks of the text mesh readers (mesh_scan.hpp).

#include "geometry/detail/mesh_scan.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace geotex::detail {
namespace {

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

// CGAL's OFF reader doubles the edge count in an int (an estimate of the half-edges), which
// overflows from 2^30 on. geotex does not use the count, but such a file would crash the
// CGAL-based tools a user may open it with next, so it stays refused.
constexpr std::int64_t kMaxOffEdges = static_cast<std::int64_t>(kMaxInt / 2);

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
    // CGAL and other OFF readers take the rest of the line of the counts as the first
    // vertex, others skip it: text there is ambiguous, so it is refused.
    if (next < tokens.size()) {
        scan.fail("not a valid OFF file: '" + printable(tokens[next].text) +
                      "' after the edge count (the vertices start on the next line)",
                  lines.line(), tokens[next].column);
    }
    h.counts_column = vertex_count_column;
    h.body_offset = lines.offset();
    return h;
}

// Declared counts against the remaining bytes, before anything is sized from them.
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

}  // namespace geotex::detail
