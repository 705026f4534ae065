// The OFF, OBJ and STL readers (geometry/detail/obj_reader.cpp, off_reader.cpp, stl_reader.cpp)
// against the PLY reader: one mesh written in every dialect must read back as the PLY of the same
// mesh, point for point and polygon for polygon; and bad input names the file, line and column.

#include <unistd.h>

#include <array>
#include <catch2/catch.hpp>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/read_window.hpp"
#include "geometry/icosphere.hpp"
#include "geometry/mesh_io.hpp"
#include "tests/fixtures.hpp"
#include "tests/mesh_io_helpers.hpp"

using namespace geotex;
using namespace geotex::test;

namespace {

// A sphere (coordinates that are not short decimals) beside a height field (exact ones),
// as the PLY reader reads it: the reference every other format must match.
PolygonSoup reference_soup() {
    const Mesh sphere = make_sphere(1.7, 2, Eigen::Vector3d(0.1, -2.3, 1e-3));
    const Mesh grid = make_grid(4, 3.0, [](double x, double y) { return 0.25 * x - y * y; });
    return read_mesh_memory(to_ply(combined(sphere, grid), true), "ref.ply").soup;
}

// Shortest text that reads back to the same double.
std::string num(double v) {
    char tmp[64];
    const auto res = std::to_chars(tmp, tmp + sizeof tmp, v);
    return std::string(tmp, res.ptr);
}

struct ObjDialect {
    std::string eol = "\n";
    std::string sep = " ";
    std::string corner = "v";  // v, v/vt, v//vn or v/vt/vn
    bool relative = false;     // negative indices, faces right after their last vertex
    bool extras = false;       // w or r g b after x y z, vt, vn, groups, materials, comments
    bool continuation = false;
    bool bom = false;
};

// The soup as OBJ in a dialect. With `relative` the faces come as soon as their vertices
// are written and count back from the last vertex written.
std::string to_obj(const PolygonSoup& s, const ObjDialect& d) {
    std::string out = d.bom ? "\xEF\xBB\xBF" : "";
    if (d.extras) {
        out += "# a test mesh" + d.eol + "mtllib test.mtl" + d.eol + "o mesh" + d.eol;
        out += "vt 0.5 0.5" + d.eol + "vn 0 0 1" + d.eol + "g all" + d.eol + "usemtl stone" +
               d.eol + "s 1" + d.eol;
    }
    std::size_t written = 0;  // vertices
    auto write_vertex = [&](std::size_t i) {
        const Eigen::Vector3d& p = s.positions[i];
        out += "v" + d.sep + num(p.x()) + d.sep + num(p.y()) + d.sep + num(p.z());
        if (d.extras) out += i % 2 == 0 ? d.sep + "1" : d.sep + "0.5 0.25 1";  // w or a colour
        out += d.eol;
        ++written;
    };
    auto write_face = [&](int f) {
        out += "f";
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            const int v = s.face_indices[j];
            const long index = d.relative ? static_cast<long>(v) - static_cast<long>(written)
                                          : static_cast<long>(v) + 1;
            std::string c = std::to_string(index);
            if (d.corner == "v/vt") c += "/1";
            if (d.corner == "v//vn") c += "//1";
            if (d.corner == "v/vt/vn") c += "/1/1";
            if (d.continuation && j == s.face_offsets[f] + 1) out += d.sep + "\\" + d.eol;
            out += d.sep + c;
        }
        if (d.extras) out += d.sep + "# face " + std::to_string(f);
        out += d.eol;
    };
    if (!d.relative) {
        for (std::size_t i = 0; i < s.positions.size(); ++i) write_vertex(i);
        for (int f = 0; f < s.num_polygons(); ++f) write_face(f);
        return out;
    }
    for (int f = 0; f < s.num_polygons(); ++f) {
        int last = 0;
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            last = std::max(last, s.face_indices[j]);
        }
        while (written <= static_cast<std::size_t>(last)) write_vertex(written);
        write_face(f);
    }
    while (written < s.positions.size()) write_vertex(written);
    return out;
}

// OFF with a keyword prefix: C adds a colour to each vertex and face, N a normal, 4 writes
// every point with w = 2 (twice the coordinates, an exact division back).
std::string to_off(const PolygonSoup& s, const std::string& keyword, const std::string& eol) {
    const bool colours = keyword.find('C') != std::string::npos;
    const bool normals = keyword.find('N') != std::string::npos;
    const bool w = keyword.find('4') != std::string::npos;
    std::string out = "# written by a test" + eol + keyword + eol + "# counts" + eol +
                      std::to_string(s.positions.size()) + " " + std::to_string(s.num_polygons()) +
                      " 0" + eol;
    for (const Eigen::Vector3d& p : s.positions) {
        const double k = w ? 2.0 : 1.0;
        out += num(k * p.x()) + " " + num(k * p.y()) + "\t" + num(k * p.z());
        if (w) out += " 2";
        if (normals) out += " 0 0 1";
        if (colours) out += " 0.5 0.5 0.5 1";
        out += eol;
    }
    for (int f = 0; f < s.num_polygons(); ++f) {
        out += std::to_string(s.face_offsets[f + 1] - s.face_offsets[f]);
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            out += " " + std::to_string(s.face_indices[j]);
        }
        if (colours) out += " 255 0 0";
        out += (f % 3 == 0 ? "  # a comment" : "") + eol;
    }
    return out;
}

// ASCII STL of a triangle soup; `one_line` puts each facet on one line.
std::string to_stl(const PolygonSoup& s, const std::string& eol, bool one_line) {
    const std::string nl = one_line ? " " : eol;
    std::string out = "solid test" + eol;
    for (int f = 0; f < s.num_polygons(); ++f) {
        out += "facet normal 0 0 1" + nl + "\touter loop" + nl;
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            const Eigen::Vector3d& p = s.positions[s.face_indices[j]];
            out += "\t\tvertex  " + num(p.x()) + " " + num(p.y()) + "   " + num(p.z()) + nl;
        }
        out += "\tendloop" + nl + "endfacet" + eol;
    }
    return out + "endsolid test" + eol;
}

std::string to_binary_stl(const PolygonSoup& s) {
    std::string out(80, ' ');
    put(out, static_cast<std::uint32_t>(s.num_polygons()), false);
    for (int f = 0; f < s.num_polygons(); ++f) {
        for (int k = 0; k < 3; ++k) put(out, 0.0F, false);
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            for (int k = 0; k < 3; ++k) {
                put(out, static_cast<float>(s.positions[s.face_indices[j]][k]), false);
            }
        }
        put(out, std::uint16_t{0}, false);
    }
    return out;
}

// What an STL reader must give for a soup: the corners in file order, equal corners merged
// into the vertex of their first appearance (computed here with an ordered map, as CGAL's
// reader does).
PolygonSoup merged_corners(const PolygonSoup& s) {
    PolygonSoup out;
    std::map<std::array<double, 3>, int> seen;
    for (int j : s.face_indices) {
        const Eigen::Vector3d& p = s.positions[j];
        const auto [it, added] =
            seen.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, static_cast<int>(seen.size()));
        if (added) out.positions.push_back(p);
        out.face_indices.push_back(it->second);
    }
    out.face_offsets = s.face_offsets;
    return out;
}

PolygonSoup as_floats(PolygonSoup s) {
    for (Eigen::Vector3d& p : s.positions) p = p.cast<float>().cast<double>();
    return s;
}

void check_same(const PolygonSoup& a, const PolygonSoup& b) {
    // Exact: every number was written in a form that reads back to the same double.
    CHECK(a.positions == b.positions);
    CHECK(a.face_offsets == b.face_offsets);
    CHECK(a.face_indices == b.face_indices);
}

}  // namespace

TEST_CASE("read_mesh_memory: OBJ dialects read back as the PLY of the same mesh",
          "[geometry][mesh_io]") {
    const PolygonSoup ref = reference_soup();
    REQUIRE(ref.num_polygons() > 100);
    std::vector<std::pair<std::string, ObjDialect>> dialects;
    dialects.push_back({"plain", {}});
    for (const char* corner : {"v/vt", "v//vn", "v/vt/vn"}) {
        ObjDialect d;
        d.corner = corner;
        dialects.push_back({corner, d});
    }
    ObjDialect relative;
    relative.relative = true;
    relative.corner = "v/vt/vn";
    dialects.push_back({"relative", relative});
    ObjDialect windows;
    windows.eol = "\r\n";
    windows.sep = "\t";
    windows.bom = true;
    windows.extras = true;
    dialects.push_back({"CRLF, tabs, BOM, w, colours, groups, materials, comments", windows});
    ObjDialect continued;
    continued.continuation = true;
    continued.extras = true;
    dialects.push_back({"continuation lines", continued});
    continued.eol = "\r\n";
    dialects.push_back({"continuation lines, CRLF", continued});
    for (const auto& [label, d] : dialects) {
        INFO(label);
        const MeshFile f = read_mesh_memory(to_obj(ref, d), "mesh.obj");
        CHECK(f.format == "obj");
        check_same(f.soup, ref);
    }
}

TEST_CASE("read_mesh_memory: OFF dialects read back as the PLY of the same mesh",
          "[geometry][mesh_io]") {
    const PolygonSoup ref = reference_soup();
    for (const char* keyword : {"OFF", "COFF", "NOFF", "CNOFF", "4OFF", "C4OFF"}) {
        for (const char* eol : {"\n", "\r\n"}) {
            INFO(keyword << (eol[0] == '\r' ? " CRLF" : " LF"));
            const MeshFile f = read_mesh_memory(to_off(ref, keyword, eol), "mesh.off");
            CHECK(f.format == "off");
            check_same(f.soup, ref);
        }
    }
    const MeshFile bom = read_mesh_memory("\xEF\xBB\xBF" + to_off(ref, "OFF", "\n"), "b.off");
    check_same(bom.soup, ref);
}

TEST_CASE("read_mesh_memory: STL merges equal corners in order of first appearance",
          "[geometry][mesh_io]") {
    const PolygonSoup ref = reference_soup();
    const PolygonSoup expected = merged_corners(ref);
    // The sphere and the grid share no point: merging gives back as many vertices.
    REQUIRE(expected.positions.size() == ref.positions.size());
    for (const char* eol : {"\n", "\r\n"}) {
        for (bool one_line : {false, true}) {
            INFO((eol[0] == '\r' ? "CRLF" : "LF") << (one_line ? ", one line per facet" : ""));
            const MeshFile f = read_mesh_memory(to_stl(ref, eol, one_line), "mesh.stl");
            CHECK(f.format == "stl");
            check_same(f.soup, expected);
        }
    }
    // Binary STL holds floats.
    const MeshFile b = read_mesh_memory(to_binary_stl(ref), "mesh.stl");
    check_same(b.soup, merged_corners(as_floats(ref)));

    // -0 and +0 are one corner (CGAL compares coordinates with ==), kept as first written.
    const std::string square =
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex -0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\n"
        "vertex 0 -0 0\nendloop\nendfacet\nfacet\nouter loop\nvertex 0 0 -0\nvertex 1 1 0\n"
        "vertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
    const MeshFile m = read_mesh_memory(square, "zero.stl");
    REQUIRE(m.soup.positions.size() == 4);
    CHECK(std::signbit(m.soup.positions[0].x()));
    CHECK(polygons(m.soup) == std::vector<std::vector<int>>{{0, 1, 2}, {1, 3, 0}, {0, 3, 2}});
}

TEST_CASE("read_mesh_memory: OFF BINARY reads as the PLY of the same mesh", "[geometry][mesh_io]") {
    const PolygonSoup ref = as_floats(reference_soup());
    std::string data = "OFF BINARY\n";
    put(data, static_cast<std::int32_t>(ref.positions.size()), true);
    put(data, static_cast<std::int32_t>(ref.num_polygons()), true);
    put(data, std::int32_t{0}, true);
    for (const Eigen::Vector3d& p : ref.positions) {
        for (int k = 0; k < 3; ++k) put(data, static_cast<float>(p[k]), true);
    }
    for (int f = 0; f < ref.num_polygons(); ++f) {
        put(data, static_cast<std::int32_t>(ref.face_offsets[f + 1] - ref.face_offsets[f]), true);
        for (int j = ref.face_offsets[f]; j < ref.face_offsets[f + 1]; ++j) {
            put(data, static_cast<std::int32_t>(ref.face_indices[j]), true);
        }
    }
    check_same(read_mesh_memory(data, "b.off").soup, ref);
}

// ---- bad input ---------------------------------------------------------------------------

TEST_CASE("read_mesh_memory: text meshes that end in the middle of a line", "[geometry][mesh_io]") {
    const ParseError obj = parse_error("v 0 0 0\nv 1 0 0\nv 0 1", "cut.obj");
    CHECK(obj.file() == "cut.obj");
    CHECK(obj.line() == 3);
    CHECK(obj.column() == 5);
    CHECK(std::string(obj.what()) == "vertex 2: expected 3 coordinates after 'v', found 2");
    const ParseError off = parse_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1", "cut.off");
    CHECK(off.file() == "cut.off");
    CHECK(off.line() == 5);
    CHECK(off.column() == 3);
    CHECK(std::string(off.what()) == "vertex 2: expected 3 coordinates, found 2");
    const ParseError face = parse_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1", "face.off");
    CHECK(face.line() == 6);
    CHECK(face.column() == 5);
    CHECK(std::string(face.what()) == "face 0: expected 3 vertex indices, found 2");
    const ParseError stl =
        parse_error("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0", "c.stl");
    CHECK(stl.file() == "c.stl");
    CHECK(stl.line() == 5);  // the 'vertex' whose coordinates the file cuts
    CHECK(stl.column() == 1);
    CHECK(std::string(stl.what()) ==
          "facet 0: expected 3 coordinates after 'vertex', found 2 before the end of the file");
    const ParseError facet =
        parse_error("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "f.stl");
    CHECK(facet.line() == 5);
    CHECK(std::string(facet.what()) == "end of file inside facet 0 (begun on line 2)");
    // A coordinate missing before the next word.
    const ParseError word = parse_error(
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0\nendloop\nendfacet\nendsolid\n",
        "w.stl");
    CHECK(word.line() == 5);
    CHECK(word.column() == 1);
    CHECK(std::string(word.what()) == "facet 0: expected 3 coordinates after 'vertex', found 2");
}

TEST_CASE("read_mesh_memory: face indices outside the vertices", "[geometry][mesh_io]") {
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const ParseError past = parse_error(head + "f 1 2 3\nf 3 2 7/1\n", "past.obj");
    CHECK(past.file() == "past.obj");
    CHECK(past.line() == 5);
    CHECK(past.column() == 7);
    CHECK(std::string(past.what()) ==
          "face 1: vertex index 7 out of range (the file has 3 vertices)");
    // A forward index is fine when the vertex comes later in the file.
    CHECK(
        read_mesh_memory("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", "fwd.obj").soup.positions.size() ==
        3);
    const ParseError before = parse_error(head + "f -1 -2 -3\nf -1 -2 -4\n", "before.obj");
    CHECK(before.line() == 5);
    CHECK(before.column() == 9);
    CHECK(std::string(before.what()) ==
          "face 1: relative vertex index -4 refers before the first vertex (3 vertices so far)");
    const ParseError huge = parse_error(head + "f 1 2 3000000000\n", "huge.obj");
    CHECK(huge.column() == 7);
    CHECK(contains(huge.what(), "vertex index 3000000000 out of range"));
    const ParseError overflow = parse_error(head + "f 1 2 99999999999999999999\n", "o.obj");
    CHECK(overflow.column() == 7);
    CHECK(contains(overflow.what(), "expected a vertex index"));
    const ParseError off = parse_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 3 1\n", "r.off");
    CHECK(off.line() == 6);
    CHECK(off.column() == 5);
    CHECK(std::string(off.what()) ==
          "face 0: vertex index 3 out of range (the file has 3 vertices)");
}

TEST_CASE("read_mesh_memory: nan, inf and overflowing coordinates in text meshes",
          "[geometry][mesh_io]") {
    struct Case {
        std::string data;
        std::string name;
        long line;
        long column;
        std::string message;
    };
    const std::string stl_head = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n";
    const std::vector<Case> cases = {
        {"v 0 0 0\nv 1 nan 0\n", "n.obj", 2, 5, "vertex 1: non-finite coordinate 'nan'"},
        {"v 0 0 0\nv 1 0 -inf\n", "i.obj", 2, 7, "vertex 1: non-finite coordinate '-inf'"},
        {"v 0 0 0\nv 1 0 +INF\n", "p.obj", 2, 7, "vertex 1: non-finite coordinate '+INF'"},
        {"v 0 0 0 NaN\n", "c.obj", 1, 9, "vertex 0: non-finite coordinate 'NaN'"},
        {"v 0 1e999 0\n", "o.obj", 1, 5, "vertex 0: coordinate '1e999' overflows a double"},
        {"v 0 1.5x 0\n", "x.obj", 1, 5, "vertex 0: expected a number, got '1.5x'"},
        {"OFF\n1 1 0\n0 inf 0\n3 0 0 0\n", "i.off", 3, 3, "vertex 0: non-finite coordinate 'inf'"},
        {"OFF\n1 1 0\n-1e400 0 0\n3 0 0 0\n", "o.off", 3, 1,
         "vertex 0: coordinate '-1e400' overflows a double"},
        {"4OFF\n1 1 0\n1 0 0 0\n3 0 0 0\n", "w.off", 3, 7,
         "vertex 0: homogeneous coordinate w = 0"},
        {"4OFF\n1 1 0\n1e300 0 0 1e-300\n3 0 0 0\n", "d.off", 3, 11,
         "vertex 0: non-finite coordinate after x/w"},
        {stl_head + "vertex 1 nan 0\n", "n.stl", 5, 10, "facet 0: non-finite coordinate 'nan'"},
        {stl_head + "vertex 1 0 1e999\n", "o.stl", 5, 12,
         "facet 0: coordinate '1e999' overflows a double"},
    };
    for (const Case& c : cases) {
        INFO(c.name << ": " << c.data);
        const ParseError e = parse_error(c.data, c.name);
        CHECK(e.file() == c.name);
        CHECK(e.line() == c.line);
        CHECK(e.column() == c.column);
        CHECK(std::string(e.what()) == c.message);
    }
    // Too small for a double is 0 (or a subnormal), as istream >> double reads it.
    const MeshFile tiny =
        read_mesh_memory("v 1e-400 0 4.9e-324\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj");
    CHECK(tiny.soup.positions[0].x() == 0.0);
    CHECK(tiny.soup.positions[0].z() > 0.0);
}

TEST_CASE("read_mesh_memory: polygons of fewer than 3 vertices and empty text meshes",
          "[geometry][mesh_io]") {
    const ParseError obj = parse_error("v 0 0 0\nv 1 0 0\nf 1 2 3\n  f 1 2\n", "two.obj");
    CHECK(obj.line() == 4);
    CHECK(obj.column() == 3);
    CHECK(std::string(obj.what()) == "face 1: polygon with 2 vertices (at least 3 needed)");
    const ParseError off = parse_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "two.off");
    CHECK(off.line() == 6);
    CHECK(off.column() == 1);
    CHECK(std::string(off.what()) == "face 0: polygon with 2 vertices (at least 3 needed)");
    const ParseError stl = parse_error(
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"
        "endfacet\nendsolid s\n",
        "two.stl");
    CHECK(stl.line() == 2);
    CHECK(std::string(stl.what()) == "facet 0: 2 vertices (STL facets are triangles)");

    for (const char* name : {"e.obj", "e.off", "e.stl"}) {
        INFO(name);
        const ParseError e = parse_error("", name);
        CHECK(e.file() == name);
    }
    CHECK(std::string(parse_error("", "e.obj").what()) == "the file has no vertices");
    CHECK(std::string(parse_error("# nothing\n\n", "c.obj").what()) == "the file has no vertices");
    CHECK(std::string(parse_error("v 0 0 0\n", "v.obj").what()) == "the file has no faces");
    CHECK(contains(parse_error("", "e.off").what(), "end of file in the OFF header"));
    CHECK(contains(parse_error("", "e.stl").what(), "too short (0 bytes) for a binary STL"));
    CHECK(std::string(parse_error("solid s\nendsolid s\n", "s.stl").what()) ==
          "the file has no faces");
}

TEST_CASE("read_mesh_memory: OBJ lines are counted across continuations and CRLF",
          "[geometry][mesh_io]") {
    const ParseError e =
        parse_error("v 0 0 0\r\nv 1 \\\r\n 0 0\r\nv 0 1 0\r\nf 1 2 \\\n3 4\r\n", "c.obj");
    CHECK(e.line() == 6);
    CHECK(e.column() == 3);
    CHECK(contains(e.what(), "vertex index 4 out of range"));
    // A backslash inside a comment continues nothing.
    const MeshFile m =
        read_mesh_memory("v 0 0 0 # C:\\dir\\\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj");
    CHECK(m.soup.positions.size() == 3);
}

// Invariants of whatever the readers accept, on files damaged at random (a seeded stand-in
// for the fuzz targets, which need clang): either a ParseError, or a soup whose polygons
// have at least 3 corners, indices in range and finite points.
TEST_CASE("read_mesh_memory: damaged OBJ, OFF and STL files give a valid soup or a ParseError",
          "[geometry][mesh_io]") {
    const PolygonSoup ref = read_mesh_memory(to_ply(tetrahedron(), true), "t.ply").soup;
    ObjDialect extras;
    extras.extras = true;
    extras.continuation = true;
    extras.corner = "v/vt/vn";
    const std::vector<std::pair<std::string, std::string>> files = {
        {to_obj(ref, extras), "d.obj"},
        {to_off(ref, "C4OFF", "\r\n"), "d.off"},
        {to_stl(ref, "\n", false), "d.stl"},
        {to_binary_stl(ref), "b.stl"}};
    const std::string alphabet = " \t\r\n#\\/-+.0123456789eEnaifvt";
    std::uint64_t state = 12345;
    auto next = [&state](std::uint64_t n) {  // a 64-bit LCG: reproducible across platforms
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<std::size_t>((state >> 33) % n);
    };
    int accepted = 0;
    int refused = 0;
    for (const auto& [text, name] : files) {
        for (int round = 0; round < 1500; ++round) {
            std::string data = text;
            const std::size_t edits = 1 + next(4);
            for (std::size_t e = 0; e < edits; ++e) {
                const std::size_t at = next(data.size());
                switch (next(3)) {
                    case 0:
                        data[at] = alphabet[next(alphabet.size())];
                        break;
                    case 1:
                        data.erase(at, 1 + next(8));
                        break;
                    default:
                        data.insert(at, 1, alphabet[next(alphabet.size())]);
                }
            }
            try {
                const PolygonSoup s = read_mesh_memory(data, name).soup;
                ++accepted;
                REQUIRE(s.num_polygons() > 0);
                REQUIRE(s.face_offsets.front() == 0);
                REQUIRE(s.face_offsets.back() == static_cast<int>(s.face_indices.size()));
                for (int f = 0; f < s.num_polygons(); ++f) {
                    REQUIRE(s.face_offsets[f + 1] - s.face_offsets[f] >= 3);
                }
                for (int i : s.face_indices) {
                    REQUIRE(i >= 0);
                    REQUIRE(i < static_cast<int>(s.positions.size()));
                }
                for (const Eigen::Vector3d& p : s.positions) REQUIRE(p.allFinite());
            } catch (const ParseError& e) {
                ++refused;
                REQUIRE(e.file() == name);
            }
        }
    }
    // Both answers occur, so the loop tests something either way.
    CHECK(accepted > 100);
    CHECK(refused > 100);
}

TEST_CASE(
    "read_mesh_file: a large file gives back what its reader has passed, and reads as "
    "its bytes do",
    "[geometry][mesh_io]") {
    // Each file is larger than a step of the window (detail::kReleaseStep), so that the
    // readers give back bytes on the way: had one looked back at them, it would have read
    // zeros and given another soup, or an error.
    const Mesh mesh = make_icosphere(8);  // 327,682 vertices, 655,360 faces
    PolygonSoup sphere;                   // the same as polygons, for the text writers
    sphere.positions = mesh.positions;
    for (const auto& f : mesh.faces) {
        sphere.face_indices.insert(sphere.face_indices.end(), f.begin(), f.end());
        sphere.face_offsets.push_back(static_cast<int>(sphere.face_indices.size()));
    }
    Mesh finer = make_icosphere(9);
    for (Eigen::Vector3d& p : finer.positions) p *= 1.1;  // not floats: written as doubles
    const std::vector<std::pair<std::string, std::string>> files = {
        {to_ply(finer, true), "mesh.ply"},  // binary PLY
        {to_ply(mesh, false), "mesh.ply"},  // ASCII PLY
        {to_obj(sphere, ObjDialect{}), "mesh.obj"}, {to_off(sphere, "OFF", "\n"), "mesh.off"},
        {to_binary_stl(sphere), "mesh.stl"},
    };
    const std::string dir = "/tmp/geotex_test_window_" + std::to_string(::getpid());
    std::filesystem::create_directories(dir);
    for (const auto& [bytes, name] : files) {
        INFO(name << ", " << bytes.size() << " bytes");
        REQUIRE(bytes.size() > detail::kReleaseStep + (std::size_t{4} << 20));
        const std::string path = dir + "/" + name;
        write_file(path, bytes);
        const std::size_t released = detail::released_read_bytes();
        const MeshFile read = read_mesh_file(path);
        CHECK(detail::released_read_bytes() > released);
        const MeshFile expected = read_mesh_memory(bytes, name);
        CHECK(read.soup.positions == expected.soup.positions);
        CHECK(read.soup.face_indices == expected.soup.face_indices);
        CHECK(read.soup.face_offsets == expected.soup.face_offsets);
        std::filesystem::remove(path);
    }
    std::filesystem::remove_all(dir);
}
