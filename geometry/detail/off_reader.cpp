// OFF, ASCII and BINARY, in one pass (text_mesh_readers.hpp); the header is scanned by
// mesh_scan.cpp. The results match CGAL's reader on the files both accept (same points, same
// polygons in the same order: tests/test_text_mesh_readers.cpp).

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
void read_off_binary(const Scan& scan, const OffHeader& h, std::string_view data,
                     PolygonCollector& polygons) {
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
    polygons.reserve_vertices(nv);
    std::uint64_t at = h.body_offset;
    for (std::uint64_t v = 0; v < nv; ++v, at += vertex_bytes) {
        const auto a = static_cast<std::size_t>(at);
        if ((v & 65535) == 65535) release_read(data.data() + a);
        const double w = h.homogeneous ? be_float(data, a + 12) : 1.0;
        const Eigen::Vector3d p(be_float(data, a) / w, be_float(data, a + 4) / w,
                                be_float(data, a + 8) / w);
        if (!p.allFinite()) {
            scan.fail("vertex " + std::to_string(v) + " (byte " + std::to_string(at) +
                      "): non-finite coordinate");
        }
        polygons.vertex(p);
    }
    // Faces need at least 16 bytes each (checked with the header): the count is safe here.
    polygons.reserve(static_cast<std::size_t>(h.num_faces),
                     static_cast<std::size_t>(h.num_faces) * 3);
    for (std::int64_t f = 0; f < h.num_faces; ++f) {
        if ((f & 65535) == 65535) release_read(data.data() + at);
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
            polygons.corner(static_cast<int>(index));
        }
        if (polygons.num_corners() > kMaxInt) scan.fail("too many face vertex indices");
        polygons.end_polygon();
    }
}

// The ASCII body: one vertex or face per line, '#' starts a comment, blank lines are skipped
// (as CGAL's OFF scanner reads it). The numbers after a vertex's coordinates (colour, normal,
// texture coordinate) and after a face's indices (colour) must be numbers and are dropped.
void read_off_ascii(const Scan& scan, const OffHeader& h, std::string_view data,
                    PolygonCollector& polygons) {
    TextCursor c(data.substr(h.body_offset), h.counts_line + 1, true, false);
    const std::size_t coords = h.homogeneous ? 4 : 3;
    // Counts are not trusted until the lines are there: reserve what the text can hold.
    const std::uint64_t body = data.size() - h.body_offset;
    polygons.reserve_vertices(static_cast<std::size_t>(
        std::min<std::uint64_t>(static_cast<std::uint64_t>(h.num_vertices), body / 6 + 1)));
    const std::size_t faces = static_cast<std::size_t>(
        std::min<std::uint64_t>(static_cast<std::uint64_t>(h.num_faces), body / 8 + 1));
    polygons.reserve(faces, 3 * faces);
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
        polygons.vertex(p);
        c.next_line();
    }
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
            polygons.corner(static_cast<int>(index));
        }
        // Numbers after the indices are a colour, which geotex drops.
        for (c.skip_blanks(); !c.at_statement_end(); c.skip_blanks()) {
            double value = 0.0;
            if (!c.number(value)) number_slow(scan, c, "face", f);
        }
        if (polygons.num_corners() > kMaxInt) scan.fail("too many face vertex indices", c.line());
        polygons.end_polygon();
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

}  // namespace

MeshFile read_off(std::string_view data, const std::string& name, const PolygonSink& sink) {
    const Scan scan{name};
    const OffHeader header = scan_off_header(scan, data);
    check_off_sizes(scan, header, data.size());
    MeshFile out;
    out.format = "off";
    PolygonCollector polygons(out.soup, sink);
    if (header.binary) {
        read_off_binary(scan, header, data, polygons);
    } else {
        read_off_ascii(scan, header, data, polygons);
    }
    polygons.finish();
    return out;
}

}  // namespace geotex::detail
