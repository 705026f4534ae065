// Wavefront OBJ in one pass (text_mesh_readers.hpp). The results match CGAL's reader on the
// files both accept (same points, same polygons in the same order:
// tests/test_text_mesh_readers.cpp).

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
void reserve_obj(std::string_view data, PolygonCollector& polygons) {
    std::size_t num_v = 0;
    std::size_t num_f = 0;
    const char* p = data.data();
    const char* end = p + data.size();
    for (std::size_t line = 1; end - p >= 2; ++line) {
        if ((p[1] == ' ' || p[1] == '\t') && (p[0] == 'v' || p[0] == 'f')) {
            ++(p[0] == 'v' ? num_v : num_f);
        }
        const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
        if (nl == nullptr) break;
        p = static_cast<const char*>(nl) + 1;
        // A large file is not all held after the count: the parse reads its pages again.
        if ((line & 65535) == 0) release_scanned(p);
    }
    if ((num_v + num_f) * 8 > data.size()) return;
    polygons.reserve_vertices(num_v);
    polygons.reserve(num_f, 3 * num_f);
}

}  // namespace

MeshFile read_obj(std::string_view data, const std::string& name, const PolygonSink& sink) {
    const Scan scan{name};
    MeshFile out;
    out.format = "obj";
    PolygonCollector polygons(out.soup, sink);
    reserve_obj(data, polygons);
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
            const auto v = static_cast<std::int64_t>(polygons.num_vertices());
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
            polygons.vertex({x[0], x[1], x[2]});
        } else if (keyword == "f") {
            const auto num_vertices = static_cast<std::int64_t>(polygons.num_vertices());
            const std::int64_t f = polygons.num_polygons();
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
                polygons.corner(static_cast<int>(index));
            }
            const std::size_t n = polygons.open_corners();
            if (n < 3) {
                scan.fail("face " + std::to_string(f) + ": polygon with " + std::to_string(n) +
                              " vertices (at least 3 needed)",
                          c.line(), keyword_column);
            }
            if (polygons.num_corners() > kMaxInt)
                scan.fail("too many face vertex indices", c.line());
            polygons.end_polygon();
        } else if (is_ignored_obj_statement(keyword)) {
            c.next_line(true);
            continue;
        } else {
            scan.fail("unknown OBJ statement '" + printable(keyword) + "'", c.line(),
                      keyword_column);
        }
        c.next_line();
    }
    const auto num_vertices = static_cast<std::int64_t>(polygons.num_vertices());
    for (const Forward& f : forward) {
        if (f.index > num_vertices) {
            scan.fail("face " + std::to_string(f.face) + ": vertex index " +
                          std::to_string(f.index) + " out of range (the file has " +
                          std::to_string(num_vertices) + " vertices)",
                      f.line, f.column);
        }
    }
    if (num_vertices == 0) scan.fail("the file has no vertices");
    polygons.finish();
    finish_soup(scan, polygons.num_vertices(), polygons, 0);
    return out;
}

}  // namespace geotex::detail
