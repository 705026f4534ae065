// OFF, OBJ and STL in one pass (text_mesh_readers.hpp). These formats used to go through
// CGAL's stream readers after a scan of ours for line-numbered errors: two passes, an
// istringstream per line and istream >> double, about 11 MB/s. Here a cursor walks the bytes
// once; the common case (a number followed by a blank) costs one std::from_chars, and the
// messages are built only when something is wrong. The results match CGAL's readers on the
// files both accept: same points, same polygons in the same order
// (tests/test_text_mesh_readers.cpp compares them with the PLY of the same mesh).

#include "geometry/detail/text_mesh_readers.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/mesh_scan.hpp"

namespace geotex::detail {
namespace {

constexpr std::uint64_t kMaxInt = static_cast<std::uint64_t>(std::numeric_limits<int>::max());

// "vertex 12": the element a message is about, built only when there is a message.
std::string place(const char* kind, std::int64_t index) {
    return std::string(kind) + " " + std::to_string(index);
}

// A position in a text with its line and column. Blanks are ASCII white space except '\n',
// which ends a statement; with `hash_comments` a '#' ends it too (the rest of the line is a
// comment); with `continuations` a backslash before the end of a line joins the next line
// (OBJ).
class TextCursor {
  public:
    TextCursor(std::string_view data, long first_line, bool hash_comments, bool continuations)
        : p_(data.data()),
          end_(data.data() + data.size()),
          line_start_(data.data()),
          line_(first_line),
          hash_(hash_comments),
          continuations_(continuations) {}

    bool at_end() const { return p_ == end_; }
    long line() const { return line_; }
    long column() const { return static_cast<long>(p_ - line_start_) + 1; }

    // Past blanks and continuations, to a token, the end of the statement or of the data.
    void skip_blanks() {
        for (;;) {
            while (p_ != end_ && is_blank(*p_)) ++p_;
            if (!continuations_ || p_ == end_ || *p_ != '\\' || !continues_at(p_)) return;
            p_ = std::find(p_, end_, '\n') + 1;  // continues_at found the '\n'
            ++line_;
            line_start_ = p_;
        }
    }

    // At the end of the statement: end of data, '\n', or a comment. Call after skip_blanks.
    bool at_statement_end() const { return p_ == end_ || *p_ == '\n' || (hash_ && *p_ == '#'); }

    // To the start of the next line (past a comment); statements continued with a backslash
    // are skipped whole when `statement` is set.
    void next_line(bool statement = false) {
        for (;;) {
            const void* nl = std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_));
            if (nl == nullptr) {
                p_ = end_;
                return;
            }
            const char* at = static_cast<const char*>(nl);
            const bool joined = statement && continuations_ && ends_with_backslash(at);
            p_ = at + 1;
            ++line_;
            line_start_ = p_;
            if (!joined) return;
        }
    }

    // The token at the cursor (up to a blank, the end of the line or a comment), unread.
    std::string_view token() const {
        const char* q = p_;
        while (!is_delimiter(q)) ++q;
        return {p_, static_cast<std::size_t>(q - p_)};
    }

    TextToken text_token() const { return {token(), column()}; }

    void skip(std::size_t n) { p_ += n; }

    // Past the rest of the token.
    void skip_token() {
        while (!is_delimiter(p_)) ++p_;
    }

    // A finite decimal number that is the whole token: read, true. Else false and unmoved
    // (the caller asks number_slow for the value or the message).
    bool number(double& value) {
        const char* first = p_;
        if (first != end_ && *first == '+') ++first;
        const auto res = std::from_chars(first, end_, value);
        if (res.ec != std::errc() || !is_delimiter(res.ptr) || !std::isfinite(value)) return false;
        p_ = res.ptr;
        return true;
    }

    // An integer at the cursor, with a '+' when `plus`; true if it ends at a delimiter or at
    // `stop` (which then stays unread).
    bool integer(std::int64_t& value, bool plus, char stop = '\n') {
        const char* first = p_;
        if (plus && first != end_ && *first == '+') ++first;
        const auto res = std::from_chars(first, end_, value);
        if (res.ec != std::errc() || !(is_delimiter(res.ptr) || *res.ptr == stop)) return false;
        p_ = res.ptr;
        return true;
    }

  private:
    static bool is_blank(char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
    }

    bool is_delimiter(const char* q) const {
        if (q == end_) return true;
        const char c = *q;
        return is_blank(c) || c == '\n' || (hash_ && c == '#') ||
               (continuations_ && c == '\\' && continues_at(q));
    }

    // A backslash at q followed by the end of its line (blanks allowed before it).
    bool continues_at(const char* q) const {
        ++q;
        while (q != end_ && is_blank(*q)) ++q;
        return q != end_ && *q == '\n';
    }

    // The line that ends at the '\n' at `nl` ends with a backslash (blanks allowed after it).
    bool ends_with_backslash(const char* nl) const {
        const char* q = nl;
        while (q != line_start_ && q != p_ && is_blank(q[-1])) --q;
        return q != line_start_ && q[-1] == '\\' && !(hash_ && line_has_comment(q - 1));
    }

    // A '#' before `q` on the current line: the backslash is inside a comment.
    bool line_has_comment(const char* q) const {
        return std::memchr(line_start_, '#', static_cast<std::size_t>(q - line_start_)) != nullptr;
    }

    const char* p_;
    const char* end_;
    const char* line_start_;
    long line_;
    bool hash_;
    bool continuations_;
};

// The number at the cursor when TextCursor::number said no: the message of what is wrong
// (non-finite, not a number, overflow); or, for a number so small that from_chars calls it
// out of range, its value (0 or a subnormal, as istream >> double reads it).
double number_slow(const Scan& scan, TextCursor& c, const char* kind, std::int64_t index) {
    const TextToken t = c.text_token();
    scan.check_number(t, c.line(), place(kind, index));
    const std::string copy(t.text);
    const double value = std::strtod(copy.c_str(), nullptr);
    c.skip(t.text.size());
    return value;
}

// The checks every reader ends with.
void finish_soup(const Scan& scan, MeshFile& out, long line) {
    if (out.soup.positions.size() > kMaxInt) {
        scan.fail("too many vertices: " + std::to_string(out.soup.positions.size()));
    }
    if (out.soup.num_polygons() == 0) scan.fail("the file has no faces", line);
}

// ---- OFF -----------------------------------------------------------------------------------

// Big-endian int32 and float32 at `at` (the caller checks that 4 bytes are there).
std::uint32_t be32(std::string_view data, std::size_t at) {
    const auto* b = reinterpret_cast<const unsigned char*>(data.data()) + at;
    return (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) |
           std::uint32_t{b[3]};
}

float be_float(std::string_view data, std::size_t at) {
    const std::uint32_t bits = be32(data, at);
    float f = 0.0F;
    std::memcpy(&f, &bits, 4);
    return f;
}

// OFF BINARY as CGAL wrote and read it: per vertex 3 floats (4 with the 4 prefix), then as
// many again for a normal with N and 2 (3) for a texture coordinate with ST (no colour in
// binary); per face an int32 count n and n int32 indices.
void read_off_binary(const Scan& scan, const OffHeader& h, std::string_view data, MeshFile& out) {
    const std::uint64_t coords = h.homogeneous ? 4 : 3;
    const std::uint64_t vertex_bytes =
        4 * (coords + (h.normals ? coords : 0) + (h.textures ? coords - 1 : 0));
    const auto nv = static_cast<std::uint64_t>(h.num_vertices);
    if (nv * vertex_bytes > data.size() - h.body_offset) {
        scan.fail("end of file in the vertices: " + std::to_string(nv) + " vertices of " +
                  std::to_string(vertex_bytes) + " bytes need " +
                  std::to_string(nv * vertex_bytes) + " bytes, but only " +
                  std::to_string(data.size() - h.body_offset) + " follow the header");
    }
    out.soup.positions.reserve(nv);
    std::uint64_t at = h.body_offset;
    for (std::uint64_t v = 0; v < nv; ++v, at += vertex_bytes) {
        const auto a = static_cast<std::size_t>(at);
        const double w = h.homogeneous ? be_float(data, a + 12) : 1.0;
        const Eigen::Vector3d p(be_float(data, a) / w, be_float(data, a + 4) / w,
                                be_float(data, a + 8) / w);
        if (!p.allFinite()) {
            scan.fail("vertex " + std::to_string(v) + " (byte " + std::to_string(at) +
                      "): non-finite coordinate");
        }
        out.soup.positions.push_back(p);
    }
    // Faces need at least 16 bytes each (checked with the header): the count is safe here.
    out.soup.face_offsets.reserve(static_cast<std::size_t>(h.num_faces) + 1);
    out.soup.face_indices.reserve(static_cast<std::size_t>(h.num_faces) * 3);
    for (std::int64_t f = 0; f < h.num_faces; ++f) {
        const std::string where =
            "face " + std::to_string(f) + " (byte " + std::to_string(at) + ")";
        if (at + 4 > data.size()) {
            scan.fail(where + ": end of file after " + std::to_string(f) + " of " +
                      std::to_string(h.num_faces) + " faces");
        }
        const auto n = static_cast<std::int64_t>(static_cast<std::int32_t>(be32(data, at)));
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
            const auto index = static_cast<std::int64_t>(static_cast<std::int32_t>(be32(data, at)));
            if (index < 0 || index >= h.num_vertices) {
                scan.fail(where + ": vertex index " + std::to_string(index) +
                          " out of range (the file has " + std::to_string(h.num_vertices) +
                          " vertices)");
            }
            out.soup.face_indices.push_back(static_cast<int>(index));
        }
        if (out.soup.face_indices.size() > kMaxInt) scan.fail("too many face vertex indices");
        out.soup.face_offsets.push_back(static_cast<int>(out.soup.face_indices.size()));
    }
}

// The ASCII body: one vertex or face per line, '#' starts a comment, blank lines are skipped
// (as CGAL's OFF scanner reads it). The numbers after a vertex's coordinates (colour, normal,
// texture coordinate) and after a face's indices (colour) must be numbers and are dropped.
void read_off_ascii(const Scan& scan, const OffHeader& h, std::string_view data, MeshFile& out) {
    TextCursor c(data.substr(h.body_offset), h.counts_line + 1, true, false);
    const std::size_t coords = h.homogeneous ? 4 : 3;
    // Counts are not trusted until the lines are there: reserve what the text can hold.
    const std::uint64_t body = data.size() - h.body_offset;
    out.soup.positions.reserve(static_cast<std::size_t>(
        std::min<std::uint64_t>(static_cast<std::uint64_t>(h.num_vertices), body / 6 + 1)));
    const std::size_t faces = static_cast<std::size_t>(
        std::min<std::uint64_t>(static_cast<std::uint64_t>(h.num_faces), body / 8 + 1));
    out.soup.face_offsets.reserve(faces + 1);
    out.soup.face_indices.reserve(3 * faces);
    // To the next line with something on it.
    auto next_record = [&](const char* what, std::int64_t i, std::int64_t n) {
        for (;;) {
            c.skip_blanks();
            if (c.at_end()) {
                scan.fail("end of file after " + std::to_string(i) + " of " + std::to_string(n) +
                              " " + what,
                          c.line() + (c.column() > 1 ? 1 : 0));
            }
            if (!c.at_statement_end()) return;
            c.next_line();
        }
    };
    for (std::int64_t v = 0; v < h.num_vertices; ++v) {
        next_record("vertices", v, h.num_vertices);
        double x[4] = {0, 0, 0, 1};
        std::size_t k = 0;
        long last_column = c.column();
        long w_column = 0;
        while (!c.at_statement_end()) {
            last_column = c.column();
            if (k == 3) w_column = last_column;
            double value = 0.0;
            if (!c.number(value)) value = number_slow(scan, c, "vertex", v);
            if (k < coords) x[k] = value;
            ++k;
            c.skip_blanks();
        }
        if (k < coords) {
            scan.fail("vertex " + std::to_string(v) + ": expected " + std::to_string(coords) +
                          " coordinates, found " + std::to_string(k),
                      c.line(), last_column);
        }
        if (h.homogeneous && x[3] == 0.0) {
            scan.fail("vertex " + std::to_string(v) + ": homogeneous coordinate w = 0", c.line(),
                      w_column);
        }
        const Eigen::Vector3d p(x[0] / x[3], x[1] / x[3], x[2] / x[3]);
        if (!p.allFinite()) {
            scan.fail("vertex " + std::to_string(v) + ": non-finite coordinate after x/w", c.line(),
                      w_column);
        }
        out.soup.positions.push_back(p);
        c.next_line();
    }
    std::vector<int>& indices = out.soup.face_indices;
    for (std::int64_t f = 0; f < h.num_faces; ++f) {
        next_record("faces", f, h.num_faces);
        std::int64_t n = 0;
        long last_column = c.column();
        if (!c.integer(n, true) || n < 0) {
            scan.fail("face " + std::to_string(f) + ": expected a vertex count, got '" +
                          printable(c.token()) + "'",
                      c.line(), c.column());
        }
        if (n < 3) {
            scan.fail("face " + std::to_string(f) + ": polygon with " + std::to_string(n) +
                          " vertices (at least 3 needed)",
                      c.line(), last_column);
        }
        for (std::int64_t j = 0; j < n; ++j) {
            c.skip_blanks();
            if (c.at_statement_end()) {
                scan.fail("face " + std::to_string(f) + ": expected " + std::to_string(n) +
                              " vertex indices, found " + std::to_string(j),
                          c.line(), last_column);
            }
            last_column = c.column();
            std::int64_t index = 0;
            if (!c.integer(index, true)) {
                scan.fail("face " + std::to_string(f) + ": expected a vertex index, got '" +
                              printable(c.token()) + "'",
                          c.line(), last_column);
            }
            if (index < 0) {
                scan.fail("face " + std::to_string(f) + ": negative vertex index " +
                              std::to_string(index),
                          c.line(), last_column);
            }
            if (index >= h.num_vertices) {
                scan.fail("face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                              " out of range (the file has " + std::to_string(h.num_vertices) +
                              " vertices)",
                          c.line(), last_column);
            }
            indices.push_back(static_cast<int>(index));
        }
        // Numbers after the indices are a colour, which geotex drops.
        for (c.skip_blanks(); !c.at_statement_end(); c.skip_blanks()) {
            double value = 0.0;
            if (!c.number(value)) number_slow(scan, c, "face", f);
        }
        if (indices.size() > kMaxInt) scan.fail("too many face vertex indices", c.line());
        out.soup.face_offsets.push_back(static_cast<int>(indices.size()));
        c.next_line();
    }
    // More records than declared: the counts are wrong.
    for (;;) {
        c.skip_blanks();
        if (c.at_end()) break;
        if (c.at_statement_end()) {
            c.next_line();
            continue;
        }
        scan.fail("'" + printable(c.token()) + "' after the last declared face: the file " +
                      "holds more than its header's counts (" + std::to_string(h.num_vertices) +
                      " vertices, " + std::to_string(h.num_faces) + " faces) describe",
                  c.line(), c.column());
    }
}

// ---- OBJ -----------------------------------------------------------------------------------

// Statements that carry no polygon geometry (display, grouping, free-form surfaces,
// superseded ones): accepted and skipped, as CGAL's reader did.
bool is_ignored_obj_statement(std::string_view s) {
    static const char* const ignored[] = {
        "vt",        "vn",       "vp",     "l",     "bevel",    "lod",      "ctech",
        "c_interp",  "usemap",   "usemtl", "stech", "d_interp", "mtllib",   "shadow_obj",
        "trace_obj", "o",        "g",      "s",     "p",        "cstype",   "deg",
        "step",      "bmat",     "con",    "curv",  "curv2",    "surf",     "parm",
        "trim",      "hole",     "scrv",   "sp",    "end",      "surf_1",   "q0_1",
        "q1_1",      "curv2d_1", "surf_2", "q0_2",  "q1_2",     "curv2d_2", "bsp",
        "bzp",       "cdc",      "cdp",    "res"};
    for (const char* k : ignored) {
        if (s == k) return true;
    }
    return false;
}

// Lines that start with "v " and "f ": enough to reserve the vectors once (lines indented
// or continued are not counted; the vectors then grow). Each such statement takes at least 8
// bytes when it is valid ("v 0 0 0\n", "f 1 2 3\n"): a file of more of them than that is
// odd, and its counts do not get to reserve memory many times its size.
void reserve_obj(std::string_view data, MeshFile& out) {
    std::size_t num_v = 0;
    std::size_t num_f = 0;
    const char* p = data.data();
    const char* end = p + data.size();
    while (end - p >= 2) {
        if ((p[1] == ' ' || p[1] == '\t') && (p[0] == 'v' || p[0] == 'f')) {
            ++(p[0] == 'v' ? num_v : num_f);
        }
        const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
        if (nl == nullptr) break;
        p = static_cast<const char*>(nl) + 1;
    }
    if ((num_v + num_f) * 8 > data.size()) return;
    out.soup.positions.reserve(num_v);
    out.soup.face_offsets.reserve(num_f + 1);
    out.soup.face_indices.reserve(3 * num_f);
}

// ---- STL -----------------------------------------------------------------------------------

// Corners with equal coordinates become one vertex, numbered by first appearance, as CGAL's
// STL reader numbered them with a std::map<Point, int>; an open-addressing table does the
// same in expected constant time. Equal means == on each coordinate, so +0 and -0 are one
// corner: the hash adds 0.0, which turns -0 into +0.
class CornerIndex {
  public:
    explicit CornerIndex(std::vector<Eigen::Vector3d>& positions) : positions_(positions) {
        slots_.assign(1024, -1);
    }

    int find_or_add(const Eigen::Vector3d& p) {
        if (2 * (positions_.size() + 1) > slots_.size()) rehash(2 * slots_.size());
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t h = hash(p) & mask;; h = (h + 1) & mask) {
            const int s = slots_[h];
            if (s < 0) {
                slots_[h] = static_cast<int>(positions_.size());
                positions_.push_back(p);
                return slots_[h];
            }
            if (positions_[static_cast<std::size_t>(s)] == p) return s;
        }
    }

  private:
    static std::uint64_t bits(double v) {
        v += 0.0;
        std::uint64_t b = 0;
        std::memcpy(&b, &v, 8);
        return b;
    }

    // Every input bit reaches the low bits that pick the slot: the sign and exponent sit in
    // the high bits of a double, and short decimals (1.0, 0.5) have all-zero low bits.
    static std::uint64_t mix(std::uint64_t h) {
        h ^= h >> 33;
        h *= 0xFF51AFD7ED558CCDULL;
        h ^= h >> 33;
        h *= 0xC4CEB9FE1A85EC53ULL;
        return h ^ (h >> 33);
    }

    static std::size_t hash(const Eigen::Vector3d& p) {
        return static_cast<std::size_t>(
            mix(bits(p.x()) ^ mix(bits(p.y()) ^ mix(bits(p.z()) + 0x9E3779B97F4A7C15ULL))));
    }

    void rehash(std::size_t size) {
        slots_.assign(size, -1);
        const std::size_t mask = size - 1;
        for (std::size_t i = 0; i < positions_.size(); ++i) {
            std::size_t h = hash(positions_[i]) & mask;
            while (slots_[h] >= 0) h = (h + 1) & mask;
            slots_[h] = static_cast<int>(i);
        }
    }

    std::vector<Eigen::Vector3d>& positions_;
    std::vector<int> slots_;  // index into positions_, -1 = empty; size a power of two
};

float le_float(std::string_view data, std::size_t at) {
    const std::uint32_t bits = le32(data, at);
    float f = 0.0F;
    std::memcpy(&f, &bits, 4);
    return f;
}

// Binary STL: n records of a normal (ignored), three corners of three floats and two
// attribute bytes (ignored), after the 84 bytes of header and count.
void read_binary_stl(const Scan& scan, std::string_view data, std::uint64_t n, MeshFile& out) {
    if (n == 0) scan.fail("the file has no faces");
    if (n > kMaxInt / 3) scan.fail("too many triangles: " + std::to_string(n));
    out.soup.face_offsets.reserve(static_cast<std::size_t>(n) + 1);
    out.soup.face_indices.reserve(3 * static_cast<std::size_t>(n));
    out.soup.positions.reserve(static_cast<std::size_t>(n) / 2 + 3);  // closed meshes: n/2 + 2
    CornerIndex corners(out.soup.positions);
    for (std::uint64_t i = 0; i < n; ++i) {
        const std::size_t record = 84 + 50 * static_cast<std::size_t>(i);
        for (std::size_t k = 3; k < 12; k += 3) {
            const std::size_t at = record + 4 * k;
            const Eigen::Vector3d p(le_float(data, at), le_float(data, at + 4),
                                    le_float(data, at + 8));
            if (!p.allFinite()) {
                std::size_t bad = at;
                while (std::isfinite(le_float(data, bad))) bad += 4;
                scan.fail("triangle " + std::to_string(i) + " of " + std::to_string(n) + " (byte " +
                          std::to_string(bad) + "): non-finite vertex coordinate");
            }
            out.soup.face_indices.push_back(corners.find_or_add(p));
        }
        out.soup.face_offsets.push_back(static_cast<int>(out.soup.face_indices.size()));
    }
}

// ASCII STL, word by word as CGAL read it (any white space, line breaks anywhere): facets of
// exactly three `vertex x y z` between `facet` and `endfacet`, inside `solid` ... `endsolid`;
// the words in between (normal and its numbers, outer loop, endloop) are skipped, the name
// after solid and endsolid too.
void read_ascii_stl(const Scan& scan, std::string_view data, MeshFile& out) {
    TextCursor c(data, 1, false, false);
    CornerIndex corners(out.soup.positions);
    // To the next word, across lines; false at the end of the data.
    auto next_word = [&c] {
        for (;;) {
            c.skip_blanks();
            if (c.at_end()) return false;
            if (!c.at_statement_end()) return true;
            c.next_line();
        }
    };
    bool in_facet = false;
    bool solid_closed = false;
    long facet_line = 0;
    int num_corners = 0;
    int triangle[3] = {0, 0, 0};
    std::int64_t facets = 0;
    while (next_word()) {
        const long line = c.line();
        const long column = c.column();
        const std::string_view word = c.token();
        c.skip(word.size());
        if (word == "facet") {
            if (in_facet) {
                scan.fail("facet " + std::to_string(facets) + ": 'facet' before 'endfacet'", line,
                          column);
            }
            in_facet = true;
            facet_line = line;
            num_corners = 0;
        } else if (word == "vertex") {
            if (!in_facet) scan.fail("'vertex' outside a facet", line, column);
            if (num_corners == 3) {
                scan.fail("facet " + std::to_string(facets) +
                              ": more than 3 vertices (STL facets are triangles)",
                          line, column);
            }
            double x[3] = {0, 0, 0};
            for (int k = 0; k < 3; ++k) {
                if (!next_word()) {
                    scan.fail("facet " + std::to_string(facets) +
                                  ": expected 3 coordinates after 'vertex', found " +
                                  std::to_string(k) + " before the end of the file",
                              line, column);
                }
                if (c.number(x[k])) continue;
                const std::string_view t = c.token();
                const char first = t[0] == '+' || t[0] == '-' ? (t.size() > 1 ? t[1] : '0') : t[0];
                const bool word_not_number =
                    ((first >= 'a' && first <= 'z') || (first >= 'A' && first <= 'Z')) &&
                    first != 'n' && first != 'N' && first != 'i' && first != 'I';
                if (word_not_number) {
                    scan.fail("facet " + std::to_string(facets) +
                                  ": expected 3 coordinates after 'vertex', found " +
                                  std::to_string(k),
                              c.line(), c.column());
                }
                x[k] = number_slow(scan, c, "facet", facets);
            }
            if (c.at_end()) break;
            triangle[num_corners++] = corners.find_or_add(Eigen::Vector3d(x[0], x[1], x[2]));
        } else if (word == "endfacet") {
            if (!in_facet) scan.fail("'endfacet' without 'facet'", line, column);
            if (num_corners != 3) {
                scan.fail("facet " + std::to_string(facets) + ": " + std::to_string(num_corners) +
                              " vertices (STL facets are triangles)",
                          facet_line, 0);
            }
            in_facet = false;
            ++facets;
            out.soup.face_indices.insert(out.soup.face_indices.end(), triangle, triangle + 3);
            if (out.soup.face_indices.size() > kMaxInt) scan.fail("too many triangles", line);
            out.soup.face_offsets.push_back(static_cast<int>(out.soup.face_indices.size()));
        } else if (word == "solid" || word == "endsolid") {
            solid_closed = word == "endsolid";
            c.next_line();  // the name
        }
    }
    const long end_line = c.line() + (c.column() > 1 ? 1 : 0);
    if (in_facet) {
        scan.fail("end of file inside facet " + std::to_string(facets) + " (begun on line " +
                      std::to_string(facet_line) + ")",
                  end_line);
    }
    if (!solid_closed) scan.fail("end of file before 'endsolid'", end_line);
    finish_soup(scan, out, 0);
}

}  // namespace

MeshFile read_off(std::string_view data, const std::string& name) {
    const Scan scan{name};
    const OffHeader header = scan_off_header(scan, data);
    check_off_sizes(scan, header, data.size());
    MeshFile out;
    out.format = "off";
    if (header.binary) {
        read_off_binary(scan, header, data, out);
    } else {
        read_off_ascii(scan, header, data, out);
    }
    return out;
}

MeshFile read_obj(std::string_view data, const std::string& name) {
    const Scan scan{name};
    MeshFile out;
    out.format = "obj";
    reserve_obj(data, out);
    std::vector<Eigen::Vector3d>& positions = out.soup.positions;
    std::vector<int>& indices = out.soup.face_indices;
    std::vector<int>& offsets = out.soup.face_offsets;
    // Indices past the vertices read so far: valid if the file has them by its end.
    struct Forward {
        std::int64_t index;
        std::int64_t face;
        long line;
        long column;
    };
    std::vector<Forward> forward;
    TextCursor c(data, 1, true, true);
    while (!c.at_end()) {
        c.skip_blanks();
        if (c.at_statement_end()) {
            c.next_line();
            continue;
        }
        const long keyword_column = c.column();
        const std::string_view keyword = c.token();
        c.skip(keyword.size());
        if (keyword == "v") {
            const auto v = static_cast<std::int64_t>(positions.size());
            double x[3] = {0, 0, 0};
            int k = 0;
            long last_column = keyword_column;
            // x y z, then optionally w or a colour r g b: all must be numbers, x y z are kept.
            for (c.skip_blanks(); !c.at_statement_end(); c.skip_blanks()) {
                last_column = c.column();
                double value = 0.0;
                if (!c.number(value)) value = number_slow(scan, c, "vertex", v);
                if (k < 3) x[k] = value;
                ++k;
            }
            if (k < 3) {
                scan.fail("vertex " + std::to_string(v) +
                              ": expected 3 coordinates after 'v', found " + std::to_string(k),
                          c.line(), last_column);
            }
            positions.emplace_back(x[0], x[1], x[2]);
        } else if (keyword == "f") {
            const auto num_vertices = static_cast<std::int64_t>(positions.size());
            const std::int64_t f = static_cast<std::int64_t>(offsets.size()) - 1;
            const std::size_t first = indices.size();
            for (c.skip_blanks(); !c.at_statement_end(); c.skip_blanks()) {
                const long column = c.column();
                std::int64_t index = 0;
                // v, v/vt, v//vn or v/vt/vn: the vertex index is the part before '/'.
                if (!c.integer(index, false, '/')) {
                    scan.fail("face " + std::to_string(f) +
                                  ": expected a vertex index (v, v/vt, v//vn or v/vt/vn), got '" +
                                  printable(c.token()) + "'",
                              c.line(), column);
                }
                c.skip_token();
                if (index == 0) {
                    scan.fail("face " + std::to_string(f) +
                                  ": vertex index 0 is invalid (OBJ counts from 1)",
                              c.line(), column);
                }
                if (index < 0) {
                    if (index < -num_vertices) {  // not -index: it overflows for INT64_MIN
                        scan.fail("face " + std::to_string(f) + ": relative vertex index " +
                                      std::to_string(index) + " refers before the first vertex (" +
                                      std::to_string(num_vertices) + " vertices so far)",
                                  c.line(), column);
                    }
                    index += num_vertices;
                } else {
                    if (index > num_vertices) {
                        if (static_cast<std::uint64_t>(index) > kMaxInt) {
                            scan.fail("face " + std::to_string(f) + ": vertex index " +
                                          std::to_string(index) + " out of range",
                                      c.line(), column);
                        }
                        forward.push_back({index, f, c.line(), column});
                    }
                    index -= 1;
                }
                indices.push_back(static_cast<int>(index));
            }
            const std::size_t n = indices.size() - first;
            if (n < 3) {
                scan.fail("face " + std::to_string(f) + ": polygon with " + std::to_string(n) +
                              " vertices (at least 3 needed)",
                          c.line(), keyword_column);
            }
            if (indices.size() > kMaxInt) scan.fail("too many face vertex indices", c.line());
            offsets.push_back(static_cast<int>(indices.size()));
        } else if (is_ignored_obj_statement(keyword)) {
            c.next_line(true);
            continue;
        } else {
            scan.fail("unknown OBJ statement '" + printable(keyword) + "'", c.line(),
                      keyword_column);
        }
        c.next_line();
    }
    const auto num_vertices = static_cast<std::int64_t>(positions.size());
    for (const Forward& f : forward) {
        if (f.index > num_vertices) {
            scan.fail("face " + std::to_string(f.face) + ": vertex index " +
                          std::to_string(f.index) + " out of range (the file has " +
                          std::to_string(num_vertices) + " vertices)",
                      f.line, f.column);
        }
    }
    if (positions.empty()) scan.fail("the file has no vertices");
    finish_soup(scan, out, 0);
    return out;
}

MeshFile read_stl(std::string_view data, const std::string& name) {
    const Scan scan{name};
    const std::uint64_t n = data.size() >= 84 ? le32(data, 80) : 0;
    const std::uint64_t binary_size = 84 + 50 * n;
    const bool solid = starts_with_solid(data);
    // A binary file whose size matches its triangle count is binary even when its free-form
    // header starts with "solid", as some exporters write it.
    bool binary = data.size() >= 84 && binary_size == data.size();
    if (!binary && !solid) {
        if (data.size() < 84) {
            scan.fail("not a valid STL file: it does not start with 'solid' and is too short (" +
                      std::to_string(data.size()) + " bytes) for a binary STL (84-byte header)");
        }
        if (binary_size > data.size()) {
            scan.fail("binary STL truncated: it declares " + std::to_string(n) +
                      " triangles, which need " + std::to_string(binary_size) +
                      " bytes, but the file has " + std::to_string(data.size()) + " bytes");
        }
        binary = true;  // extra bytes after the triangles are ignored
    }
    MeshFile out;
    out.format = "stl";
    if (binary) {
        read_binary_stl(scan, data, n, out);
    } else {
        read_ascii_stl(scan, data, out);
    }
    return out;
}

}  // namespace geotex::detail
