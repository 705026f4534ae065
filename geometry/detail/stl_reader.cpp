// STL, ASCII and binary, in one pass (text_mesh_readers.hpp), equal corners merged in order
// of first appearance. The results match CGAL's reader on the files both accept
// (tests/test_text_mesh_readers.cpp).

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
#include "geometry/detail/polygon_collector.hpp"
#include "geometry/detail/read_window.hpp"
#include "geometry/detail/text_cursor.hpp"
#include "geometry/detail/text_mesh_readers.hpp"

namespace geotex::detail {
namespace {

using namespace text_mesh;

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
void read_binary_stl(const Scan& scan, std::string_view data, std::uint64_t n, MeshFile& out,
                     PolygonCollector& polygons) {
    if (n == 0) scan.fail("the file has no faces");
    if (n > kMaxInt / 3) scan.fail("too many triangles: " + std::to_string(n));
    polygons.reserve(static_cast<std::size_t>(n), 3 * static_cast<std::size_t>(n));
    out.soup.positions.reserve(static_cast<std::size_t>(n) / 2 + 3);  // closed meshes: n/2 + 2
    CornerIndex corners(out.soup.positions);
    for (std::uint64_t i = 0; i < n; ++i) {
        const std::size_t record = 84 + 50 * static_cast<std::size_t>(i);
        if ((i & 65535) == 65535) release_read(data.data() + record);
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
            polygons.corner(corners.find_or_add(p));
        }
        polygons.end_polygon();
    }
}

// ASCII STL, word by word as CGAL read it (any white space, line breaks anywhere): facets of
// exactly three `vertex x y z` between `facet` and `endfacet`, inside `solid` ... `endsolid`;
// the words in between (normal and its numbers, outer loop, endloop) are skipped, the name
// after solid and endsolid too.
void read_ascii_stl(const Scan& scan, std::string_view data, MeshFile& out,
                    PolygonCollector& polygons) {
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
            for (const int corner : triangle) polygons.corner(corner);
            if (polygons.num_corners() > kMaxInt) scan.fail("too many triangles", line);
            polygons.end_polygon();
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
    // Not polygons.num_vertices(): the corners' positions stay in the soup (CornerIndex).
    finish_soup(scan, out.soup.positions.size(), polygons, 0);
}

}  // namespace

MeshFile read_stl(std::string_view data, const std::string& name, const PolygonSink& sink) {
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
    PolygonCollector polygons(out.soup, sink);
    if (binary) {
        read_binary_stl(scan, data, n, out, polygons);
    } else {
        read_ascii_stl(scan, data, out, polygons);
    }
    polygons.finish();
    return out;
}

}  // namespace geotex::detail
