#include <catch2/catch.hpp>
#include <string>

#include "common/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "tests/mesh_io_helpers.hpp"

using namespace geotex;
using namespace geotex::test;

// ---- OFF, OBJ and STL (CGAL readers behind a line-by-line check) ----------------------

TEST_CASE("read_mesh_memory: OFF with a quad, a pentagon, comments and colours",
          "[geometry][mesh_io]") {
    const std::string data =
        "OFF\n"
        "# a house: square and roof\n"
        "6 2 0\n"
        "0 0 0\n"
        "1 0 0\n"
        "1 1 0  # a comment after a vertex\n"
        "0 1 0\n"
        "\n"
        "0.5 1.5 0\n"
        "2 2 2\n"
        "4 0 1 2 3\n"
        "5 0 1 2 4 3 255 0 0\n";
    const MeshFile m = read_mesh_memory(data, "house.off");
    CHECK(m.format == "off");
    REQUIRE(m.soup.positions.size() == 6);
    CHECK(m.soup.positions[4] == Eigen::Vector3d(0.5, 1.5, 0));
    CHECK(polygons(m.soup) == std::vector<std::vector<int>>{{0, 1, 2, 3}, {0, 1, 2, 4, 3}});
}

TEST_CASE("read_mesh_memory: malformed OFF files name the line", "[geometry][mesh_io]") {
    const std::string head = "OFF\n3 1 0\n0 0 0\n1 0 0\n";
    const ParseError nan = parse_error(head + "0 nan 0\n3 0 1 2\n", "n.off");
    CHECK(nan.line() == 5);
    CHECK(nan.column() == 3);
    CHECK(contains(nan.what(), "vertex 2: non-finite coordinate 'nan'"));
    const ParseError range = parse_error(head + "0 1 0\n3 0 1 3\n", "r.off");
    CHECK(range.line() == 6);
    CHECK(range.column() == 7);
    CHECK(contains(range.what(), "vertex index 3 out of range"));
    const ParseError negative = parse_error(head + "0 1 0\n3 0 -1 2\n", "m.off");
    CHECK(contains(negative.what(), "negative vertex index -1"));
    const ParseError truncated = parse_error(head + "0 1 0\n", "t.off");
    CHECK(truncated.line() == 6);
    CHECK(contains(truncated.what(), "end of file after 0 of 1 faces"));
    const ParseError declared = parse_error("OFF\n3 100 0\n0 0 0\n1 0 0\n0 1 0\n", "d.off");
    CHECK(declared.line() == 2);
    CHECK(contains(declared.what(), "need at least 206 bytes, but only 18 bytes follow"));
    const ParseError huge = parse_error("OFF\n3 1000000000000 0\n", "h.off");
    CHECK(huge.line() == 2);
    const ParseError keyword = parse_error("MESH\n3 1 0\n", "k.off");
    CHECK(keyword.line() == 1);
    CHECK(contains(keyword.what(), "not a valid OFF file"));
    const ParseError count = parse_error(head + "0 1 0\n3 0 1\n", "c.off");
    CHECK(contains(count.what(), "expected 3 vertex indices, found 2"));
    // A face more than the header declares: CGAL would drop it without a word.
    const ParseError extra = parse_error(head + "0 1 0\n3 0 1 2\n3 0 2 1\n", "e.off");
    CHECK(extra.line() == 7);
    CHECK(extra.column() == 1);
    CHECK(contains(extra.what(), "after the last declared face"));
    CHECK(read_mesh_memory(head + "0 1 0\n3 0 1 2\n# end\n\n", "ok.off").soup.num_polygons() == 1);
}

TEST_CASE("read_mesh_memory: OBJ with slashes, relative indices, quads and polygons",
          "[geometry][mesh_io]") {
    const std::string data =
        "# exported by hand\n"
        "mtllib house.mtl\n"
        "o house\n"
        "v 0 0 0\n"
        "v 1 0 0\n"
        "v 1 1 0\n"
        "v 0 1 0 1.0\n"
        "vt 0 0\n"
        "vn 0 0 1\n"
        "g walls\n"
        "usemtl brick\n"
        "s off\n"
        "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
        "v 0.5 1.5 0\n"
        "f 1//1 2//1 3//1 -1 4//1\n"
        "f\t-5\t-4\t-1\n"
        "l 1 2\n"
        "f 1/1 3/1 4/1 # a comment\n";
    const MeshFile m = read_mesh_memory(data, "house.OBJ");
    CHECK(m.format == "obj");
    REQUIRE(m.soup.positions.size() == 5);
    CHECK(m.soup.positions[3] == Eigen::Vector3d(0, 1, 0));
    CHECK(polygons(m.soup) ==
          std::vector<std::vector<int>>{{0, 1, 2, 3}, {0, 1, 2, 4, 3}, {0, 1, 4}, {0, 2, 3}});
}

TEST_CASE("read_mesh_memory: malformed OBJ files name the line", "[geometry][mesh_io]") {
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const ParseError range = parse_error(head + "f 1 2 4\n", "r.obj");
    CHECK(range.line() == 4);
    CHECK(range.column() == 7);
    CHECK(contains(range.what(), "vertex index 4 out of range (the file has 3 vertices)"));
    const ParseError zero = parse_error(head + "f 0 1 2\n", "z.obj");
    CHECK(contains(zero.what(), "vertex index 0 is invalid"));
    const ParseError relative = parse_error(head + "f 1 2 -4\n", "n.obj");
    CHECK(relative.column() == 7);
    CHECK(contains(relative.what(), "relative vertex index -4"));
    const ParseError nan = parse_error("v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", "i.obj");
    CHECK(nan.line() == 2);
    CHECK(nan.column() == 5);
    const ParseError statement = parse_error(head + "xyz 1 2\nf 1 2 3\n", "s.obj");
    CHECK(statement.line() == 4);
    CHECK(contains(statement.what(), "unknown OBJ statement 'xyz'"));
    const ParseError faces = parse_error(head, "p.obj");
    CHECK(contains(faces.what(), "has no faces"));
    const ParseError two = parse_error(head + "f 1 2\n", "t.obj");
    CHECK(contains(two.what(), "polygon with 2 vertices"));
}

TEST_CASE("read_mesh_memory: ASCII STL merges shared corners", "[geometry][mesh_io]") {
    const std::string data =
        "solid square\n"
        "  facet normal 0 0 1\n"
        "    outer loop\n"
        "      vertex 0 0 0\n"
        "      vertex 1 0 0\n"
        "      vertex 0 1 0\n"
        "    endloop\n"
        "  endfacet\n"
        "  facet normal 0 0 1\n"
        "    outer loop\n"
        "      vertex 1 0 0\n"
        "      vertex 1 1 0\n"
        "      vertex 0 1 0\n"
        "    endloop\n"
        "  endfacet\n"
        "endsolid square\n";
    const MeshFile m = read_mesh_memory(data, "square.stl");
    CHECK(m.format == "stl");
    CHECK(m.soup.positions.size() == 4);
    CHECK(polygons(m.soup) == std::vector<std::vector<int>>{{0, 1, 2}, {1, 3, 2}});

    std::string four = data;
    four.insert(four.find("    endloop\n"), "      vertex 2 2 2\n");
    const ParseError e = parse_error(four, "four.stl");
    CHECK(e.line() == 7);
    CHECK(contains(e.what(), "more than 3 vertices"));
    std::string nan = data;
    nan.replace(nan.find("vertex 1 0 0"), 12, "vertex 1 NaN 0");
    CHECK(parse_error(nan, "nan.stl").line() == 5);
    CHECK(contains(parse_error(data.substr(0, 150), "cut.stl").what(), "end of file"));
}

TEST_CASE("read_mesh_memory: binary STL, also with a header starting with 'solid'",
          "[geometry][mesh_io]") {
    auto binary_stl = [](const std::string& header, const std::vector<std::array<float, 9>>& tris) {
        std::string s = header;
        s.resize(80, ' ');
        put(s, static_cast<std::uint32_t>(tris.size()), false);
        for (const auto& t : tris) {
            for (int k = 0; k < 3; ++k) put(s, 0.0F, false);  // normal
            for (float c : t) put(s, c, false);
            put(s, std::uint16_t{0}, false);
        }
        return s;
    };
    const std::vector<std::array<float, 9>> square = {{0, 0, 0, 1, 0, 0, 0, 1, 0},
                                                      {1, 0, 0, 1, 1, 0, 0, 1, 0}};
    for (const char* header : {"binary STL from a test", "solid but binary"}) {
        const MeshFile m = read_mesh_memory(binary_stl(header, square), "b.stl");
        CHECK(m.format == "stl");
        CHECK(m.soup.positions.size() == 4);
        CHECK(polygons(m.soup) == std::vector<std::vector<int>>{{0, 1, 2}, {1, 3, 2}});
    }
    const std::string full = binary_stl("x", square);
    const ParseError cut = parse_error(full.substr(0, full.size() - 10), "cut.stl");
    CHECK(contains(cut.what(), "declares 2 triangles, which need 184 bytes"));
    auto with_nan = square;
    with_nan[1][4] = std::numeric_limits<float>::quiet_NaN();
    const ParseError nan = parse_error(binary_stl("x", with_nan), "nan.stl");
    CHECK(contains(nan.what(), "triangle 1 of 2 (byte 162): non-finite"));
}

// ---- files -------------------------------------------------------------------------------
