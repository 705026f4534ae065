#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/errors.hpp"
#include "geometry/icosphere.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/scratch_file.hpp"
#include "tests/fixtures.hpp"
#include "tests/mesh_io_helpers.hpp"

using namespace geotex;

using namespace geotex::test;

// ---- PLY round trips ---------------------------------------------------------------------

TEST_CASE("write_ply: ASCII round trip is exact", "[geometry][mesh_io]") {
    const Mesh m = tetrahedron();
    const MeshFile f = read_mesh_memory(to_ply(m, false), "t.ply");
    CHECK(f.format == "ply-ascii");
    // Exact equality: doubles are written in shortest round-trip form.
    CHECK(f.soup.positions == m.positions);
    CHECK(polygons(f.soup) == polygons(m));
    CHECK(f.face_properties.empty());
}

TEST_CASE("write_ply: binary little endian round trip is exact", "[geometry][mesh_io]") {
    const Mesh m = tetrahedron();
    const MeshFile f = read_mesh_memory(to_ply(m, true), "t.ply");
    CHECK(f.format == "ply-binary-le");
    CHECK(f.soup.positions == m.positions);
    CHECK(polygons(f.soup) == polygons(m));
}

TEST_CASE("write_ply: float coordinates when all are floats, else double", "[geometry][mesh_io]") {
    const Mesh floats = tetrahedron(0.5);  // 0, 1 and 0.5 are exact floats
    const Mesh doubles = tetrahedron(0.1);
    for (bool binary : {false, true}) {
        const std::string f = to_ply(floats, binary);
        const std::string d = to_ply(doubles, binary);
        CHECK(contains(f, "property float x\nproperty float y\nproperty float z\n"));
        CHECK(contains(d, "property double x\nproperty double y\nproperty double z\n"));
        CHECK(read_mesh_memory(f, "f.ply").soup.positions == floats.positions);
        CHECK(read_mesh_memory(d, "d.ply").soup.positions == doubles.positions);
    }
    // Binary sizes: 4 vertices of 3 floats or 3 doubles, 4 faces of 1 + 3 * 4 bytes.
    const std::string fb = to_ply(floats, true);
    const std::string db = to_ply(doubles, true);
    CHECK(fb.size() - fb.find("end_header\n") - 11 == 4 * 12 + 4 * 13);
    CHECK(db.size() - db.find("end_header\n") - 11 == 4 * 24 + 4 * 13);
}

TEST_CASE("PlyWriter: blocks of vertices and faces give write_ply's bytes", "[geometry][mesh_io]") {
    Mesh m = make_icosphere(2);
    for (auto& p : m.positions) p *= 1.1;  // doubles, not floats
    std::vector<int> texel(m.faces.size());
    for (std::size_t f = 0; f < texel.size(); ++f) texel[f] = static_cast<int>(f % 5) - 1;
    // The labels `values` as a texel id and a colour channel through a table.
    const auto attributes_of = [](const std::vector<int>* values) {
        FaceAttribute red("red", PlyScalarType::UInt8, values);
        red.table = {7, 8, 9, 10, 11};
        red.table_first = -1;
        return std::vector<FaceAttribute>{{"texel", PlyScalarType::Int32, values}, red};
    };
    const std::vector<FaceAttribute> attributes = attributes_of(&texel);
    for (bool binary : {false, true}) {
        PlyWriteOptions w;
        w.binary = binary;
        w.comments = {"blocks"};
        std::ostringstream whole, blocks;
        write_ply(whole, m, attributes, w);
        // The vertices as a tiled run's join has them: mapped from a scratch file.
        const test::TempDir dir("ply_writer_blocks");
        PositionFile mapped(dir.path());
        mapped.append(m.positions);
        const PositionSpan positions = mapped.positions();
        PlyWriter ply(blocks, positions.size(), m.faces.size(), ply_fits_float(positions),
                      attributes, w);
        // Vertices in two blocks, faces in blocks of 13 with their labels.
        const std::size_t half = positions.size() / 2;
        ply.vertices({positions.begin(), half});
        ply.vertices({positions.begin() + half, positions.size() - half});
        for (std::size_t first = 0; first < m.faces.size(); first += 13) {
            const long n = static_cast<long>(std::min<std::size_t>(13, m.faces.size() - first));
            const auto f0 = m.faces.begin() + static_cast<long>(first);
            const auto t0 = texel.begin() + static_cast<long>(first);
            const std::vector<int> labels(t0, t0 + n);
            ply.faces({f0, f0 + n}, attributes_of(&labels));
        }
        ply.finish();
        CHECK(blocks.str() == whole.str());
        CHECK(read_mesh_memory(blocks.str(), "b.ply").soup.positions == m.positions);
    }
    // Blocks that do not add up to the header's counts are the caller's mistake.
    std::ostringstream out;
    PlyWriter short_ply(out, m.positions.size(), m.faces.size(), false, {}, {});
    CHECK_THROWS_AS(short_ply.faces({m.faces[0]}, {}), std::logic_error);
    short_ply.vertices(m.positions);
    CHECK_THROWS_AS(short_ply.finish(), std::logic_error);
    // A block's value outside its table names the face by its index in the whole mesh.
    PlyWriter table_ply(out, m.positions.size(), m.faces.size(), false, attributes, {});
    table_ply.vertices(m.positions);
    const std::vector<int> good = {0, 1}, bad = {0, 9};
    table_ply.faces({m.faces[0], m.faces[1]}, attributes_of(&good));
    CHECK_THROWS_WITH(table_ply.faces({m.faces[2], m.faces[3]}, attributes_of(&bad)),
                      Catch::Contains("face 3 has value 9, outside its table"));
    CHECK_THROWS_WITH(table_ply.faces({m.faces[2]}, attributes_of(&bad)),
                      Catch::Contains("has 2 values, but the block of faces has 1 faces"));
}

TEST_CASE("write_ply: a value just off a float is written as double", "[geometry][mesh_io]") {
    Mesh m = tetrahedron(0.5);
    m.positions[3].z() = std::nextafter(0.5, 1.0);  // not a float, one double ulp away
    const std::string text = to_ply(m, true);
    CHECK(contains(text, "property double z\n"));
    CHECK(read_mesh_memory(text, "n.ply").soup.positions[3].z() == m.positions[3].z());
}

TEST_CASE("write_ply: ASCII output is the exact expected text", "[geometry][mesh_io]") {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5}};
    m.faces = {{{0, 1, 2}}};
    const std::string text =
        to_ply(m, false, {{"texel", PlyScalarType::Int32, {-1}}}, {"made by test_mesh_io"});
    CHECK(text ==
          "ply\n"
          "format ascii 1.0\n"
          "comment made by test_mesh_io\n"
          "element vertex 3\n"
          "property float x\n"
          "property float y\n"
          "property float z\n"
          "element face 1\n"
          "property list uchar int vertex_indices\n"
          "property int texel\n"
          "end_header\n"
          "0 0 0\n"
          "1 0 0\n"
          "0 1 0.5\n"
          "3 0 1 2 -1\n");
}

TEST_CASE("write_ply: face attributes round trip as face properties", "[geometry][mesh_io]") {
    const Mesh m = tetrahedron();
    const std::vector<FaceAttribute> attrs = {
        {"texel", PlyScalarType::Int32, {-1, 0, 70000, -2147483647}},
        {"label", PlyScalarType::UInt8, {0, 1, 255, 7}}};
    for (bool binary : {false, true}) {
        const MeshFile f = read_mesh_memory(to_ply(m, binary, attrs), "a.ply");
        REQUIRE(f.face_properties.size() == 2);
        CHECK(f.face_properties[0].name == "texel");
        CHECK(f.face_properties[0].values == std::vector<double>{-1, 0, 70000, -2147483647});
        CHECK(f.face_properties[1].name == "label");
        CHECK(f.face_properties[1].values == std::vector<double>{0, 1, 255, 7});
    }
}

TEST_CASE("write_ply: rejects attributes of the wrong size or range", "[geometry][mesh_io]") {
    const Mesh m = tetrahedron();
    std::ostringstream out;
    REQUIRE_THROWS_AS(write_ply(out, m, {{"texel", PlyScalarType::Int32, {1, 2, 3}}}),
                      InvalidInput);
    REQUIRE_THROWS_AS(write_ply(out, m, {{"label", PlyScalarType::UInt8, {0, 1, 256, 0}}}),
                      InvalidInput);
    REQUIRE_THROWS_AS(write_ply(out, m, {{"two words", PlyScalarType::Int32, {0, 0, 0, 0}}}),
                      InvalidInput);
    Mesh bad = m;
    bad.faces[1][2] = 4;
    REQUIRE_THROWS_AS(write_ply(out, bad, {}), InvalidInput);
    bad = m;
    bad.positions[0].x() = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_AS(write_ply(out, bad, {}), InvalidInput);
}

TEST_CASE("write_ply: attributes read from the caller's array and through a table",
          "[geometry][mesh_io]") {
    const Mesh m = tetrahedron();
    const std::vector<int> texture = {-1, 0, 2, 1};
    FaceAttribute shared("texture", PlyScalarType::Int32, &texture);
    FaceAttribute mapped("green", PlyScalarType::UInt8, &texture);
    mapped.table = {7, 100, 0, 255};  // -1 -> 7, 0 -> 100, 1 -> 0, 2 -> 255
    mapped.table_first = -1;
    // The same bytes as attributes that own the values written.
    for (bool binary : {false, true}) {
        const std::string viewed = to_ply(m, binary, {shared, mapped});
        CHECK(viewed == to_ply(m, binary,
                               {{"texture", PlyScalarType::Int32, texture},
                                {"green", PlyScalarType::UInt8, {7, 100, 255, 0}}}));
        const MeshFile f = read_mesh_memory(viewed, "a.ply");
        REQUIRE(f.face_properties.size() == 2);
        CHECK(f.face_properties[1].values == std::vector<double>{7, 100, 255, 0});
    }
    std::ostringstream out;
    // A value outside the table, and a value that the table maps outside a uchar.
    FaceAttribute short_table = mapped;
    short_table.table.pop_back();
    CHECK_THROWS_WITH(write_ply(out, m, {short_table}),
                      Catch::Contains("face 2 has value 2, outside its table"));
    FaceAttribute too_big = mapped;
    too_big.table[0] = 256;
    CHECK_THROWS_WITH(write_ply(out, m, {too_big}), Catch::Contains("face 0 has value 256"));
    const std::vector<int> three = {0, 0, 0};
    CHECK_THROWS_AS(write_ply(out, m, {{"texture", PlyScalarType::Int32, &three}}), InvalidInput);
}

TEST_CASE("read_mesh_memory: binary big endian PLY with mixed types", "[geometry][mesh_io]") {
    std::string data =
        "ply\n"
        "format binary_big_endian 1.0\n"
        "comment mixed types, an extra element and skipped properties\n"
        "element vertex 3\n"
        "property double x\n"
        "property short y\n"
        "property float32 z\n"
        "property uchar red\n"
        "element edge 1\n"
        "property list uint8 int32 vertices\n"
        "element face 2\n"
        "property list uint16 uint32 vertex_index\n"
        "property int8 flag\n"
        "property list uchar float texcoord\n"
        "property float64 quality\n"
        "end_header\n";
    const double xs[3] = {0.1, 1.0, -2.5};
    const std::int16_t ys[3] = {0, -3, 300};
    const float zs[3] = {0.25F, 1.5F, -1.0F};
    for (int i = 0; i < 3; ++i) {
        put(data, xs[i], true);
        put(data, ys[i], true);
        put(data, zs[i], true);
        put(data, static_cast<std::uint8_t>(200), true);
    }
    put(data, static_cast<std::uint8_t>(2), true);  // the edge
    put(data, std::int32_t{0}, true);
    put(data, std::int32_t{1}, true);
    const std::uint32_t faces[2][3] = {{0, 1, 2}, {2, 1, 0}};
    for (int f = 0; f < 2; ++f) {
        put(data, std::uint16_t{3}, true);
        for (std::uint32_t v : faces[f]) put(data, v, true);
        put(data, static_cast<std::int8_t>(f == 0 ? -5 : 5), true);
        put(data, static_cast<std::uint8_t>(2), true);
        put(data, 0.5F, true);
        put(data, 0.75F, true);
        put(data, 0.125 * (f + 1), true);
    }
    const MeshFile m = read_mesh_memory(data, "be.PLY");
    CHECK(m.format == "ply-binary-be");
    REQUIRE(m.soup.positions.size() == 3);
    for (int i = 0; i < 3; ++i) {
        CHECK(m.soup.positions[i] == Eigen::Vector3d(xs[i], ys[i], zs[i]));
    }
    CHECK(polygons(m.soup) == std::vector<std::vector<int>>{{0, 1, 2}, {2, 1, 0}});
    REQUIRE(m.face_properties.size() == 2);
    CHECK(m.face_properties[0].name == "flag");
    CHECK(m.face_properties[0].values == std::vector<double>{-5, 5});
    CHECK(m.face_properties[1].name == "quality");
    CHECK(m.face_properties[1].values == std::vector<double>{0.125, 0.25});

    // The same file in little endian reads the same.
    std::string le = data.substr(0, data.find("end_header\n") + 11);
    le.replace(le.find("binary_big_endian"), 17, "binary_little_endian");
    for (int i = 0; i < 3; ++i) {
        put(le, xs[i], false);
        put(le, ys[i], false);
        put(le, zs[i], false);
        put(le, static_cast<std::uint8_t>(200), false);
    }
    put(le, static_cast<std::uint8_t>(2), false);
    put(le, std::int32_t{0}, false);
    put(le, std::int32_t{1}, false);
    for (int f = 0; f < 2; ++f) {
        put(le, std::uint16_t{3}, false);
        for (std::uint32_t v : faces[f]) put(le, v, false);
        put(le, static_cast<std::int8_t>(f == 0 ? -5 : 5), false);
        put(le, static_cast<std::uint8_t>(2), false);
        put(le, 0.5F, false);
        put(le, 0.75F, false);
        put(le, 0.125 * (f + 1), false);
    }
    const MeshFile l = read_mesh_memory(le, "le.ply");
    CHECK(l.format == "ply-binary-le");
    CHECK(l.soup.positions == m.soup.positions);
    CHECK(polygons(l.soup) == polygons(m.soup));
    CHECK(l.face_properties[1].values == m.face_properties[1].values);
}

TEST_CASE("read_mesh_memory: ASCII PLY with type aliases, polygons and CRLF",
          "[geometry][mesh_io]") {
    const std::string data =
        "ply\r\n"
        "format ascii 1.0\r\n"
        "comment a quad and a triangle\r\n"
        "obj_info generated in a test\r\n"
        "element vertex 5\r\n"
        "property int16 x\r\n"
        "property uint8 y\r\n"
        "property float64 z\r\n"
        "property list uchar float normal_list\r\n"
        "element face 2\r\n"
        "property list int8 int vertex_indices\r\n"
        "property uint texel\r\n"
        "end_header\r\n"
        "0 0 0 0\r\n"
        "1 0 +0.5 2 0.1 0.2\r\n"
        "-1 1 0 0\r\n"
        "0 1 1e-3 1 7\r\n"
        "2 2 2 0\r\n"
        "4 0 1 2 3 4000000000\r\n"
        "3 3 2 1 0\r\n";
    const MeshFile m = read_mesh_memory(data, "q.ply");
    CHECK(m.format == "ply-ascii");
    CHECK(m.soup.positions[1] == Eigen::Vector3d(1, 0, 0.5));
    CHECK(m.soup.positions[2] == Eigen::Vector3d(-1, 1, 0));
    CHECK(m.soup.positions[3] == Eigen::Vector3d(0, 1, 1e-3));
    CHECK(polygons(m.soup) == std::vector<std::vector<int>>{{0, 1, 2, 3}, {3, 2, 1}});
    REQUIRE(m.face_properties.size() == 1);
    CHECK(m.face_properties[0].values == std::vector<double>{4000000000.0, 0.0});
}

// ---- PLY errors --------------------------------------------------------------------------

TEST_CASE("read_mesh_memory: truncated binary PLY names the face and byte", "[geometry][mesh_io]") {
    const std::string full = to_ply(tetrahedron(), true);
    const std::string cut = full.substr(0, full.size() - 5);
    const ParseError e = parse_error(cut, "cut.ply");
    CHECK(e.file() == "cut.ply");
    CHECK(e.line() == 7);  // the face count in the header
    CHECK(std::string(e.what()) ==
          "face 3 of 4: truncated at byte " + std::to_string(cut.size()) +
              "; the header declares 4 'face' elements, which need at least 52 bytes of binary "
              "data, but only 47 bytes remain in the file");
    // Cut inside the vertices: the fixed-size vertex block is checked as a whole.
    const std::size_t body = full.find("end_header\n") + 11;
    const ParseError v = parse_error(full.substr(0, body + 30), "v.ply");
    CHECK(contains(v.what(), "vertex 1 of 4: truncated at byte"));
}

TEST_CASE("read_mesh_memory: binary PLY of quads truncated inside a face", "[geometry][mesh_io]") {
    // Two quads need 2 * 17 bytes; 30 pass the check against the triangle minimum (2 * 13),
    // so the end is found while reading the second quad.
    std::string data =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
        "property float y\nproperty float z\nelement face 2\n"
        "property list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 12; ++i) put(data, static_cast<float>(i % 2), false);
    for (int f = 0; f < 2; ++f) {
        put(data, static_cast<std::uint8_t>(4), false);
        for (std::int32_t v : {0, 1, 2, 3}) put(data, v, false);
    }
    data.resize(data.size() - 4);
    const ParseError e = parse_error(data, "q.ply");
    CHECK(std::string(e.what()) == "face 1 of 2: truncated at byte " + std::to_string(data.size()));
}

TEST_CASE("read_mesh_memory: truncated ASCII PLY names the line", "[geometry][mesh_io]") {
    const std::string data = std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1";
    const ParseError e = parse_error(data, "t.ply");
    CHECK(e.line() == 13);
    CHECK(contains(e.what(), "face 0 of 1: end of file"));
    const ParseError v = parse_error(std::string(kTriangleHeader) + "0 0 0\n1 0", "v.ply");
    CHECK(v.line() == 11);
    CHECK(contains(v.what(), "vertex 1 of 3: end of file"));
}

TEST_CASE("read_mesh_memory: counts that the data cannot hold", "[geometry][mesh_io]") {
    // 4 vertices declared, 3 given: the face line is read as the fourth vertex, and what is
    // left of it as a polygon of 2 vertices.
    std::string data = kTriangleHeader;
    data.replace(data.find("vertex 3"), 8, "vertex 4");
    data += "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const ParseError e = parse_error(data, "c.ply");
    CHECK(e.line() == 13);
    CHECK(e.column() == 7);
    CHECK(contains(e.what(), "face 0 of 1: polygon with 2 vertices"));
    // Binary: the declared count is checked against the bytes before reading.
    std::string bin = to_ply(tetrahedron(), true);
    bin.replace(bin.find("element face 4"), 14, "element face 9");
    const ParseError b = parse_error(bin, "b.ply");
    CHECK(b.line() == 7);
    CHECK(contains(b.what(), "face 4 of 9: truncated at byte"));
    CHECK(contains(b.what(), "declares 9 'face' elements, which need at least 117 bytes"));
    // Not a number.
    std::string neg = kTriangleHeader;
    neg.replace(neg.find("vertex 3"), 8, "vertex -3");
    const ParseError n = parse_error(neg, "n.ply");
    CHECK(n.line() == 3);
    CHECK(n.column() == 16);
    CHECK(contains(n.what(), "non-negative integer"));
}

TEST_CASE("read_mesh_memory: a header declaring 10^12 faces fails fast", "[geometry][mesh_io]") {
    for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
        std::string data = kTriangleHeader;
        data.replace(data.find("ascii"), 5, format);
        data.replace(data.find("face 1"), 6, "face 1000000000000");
        data += std::string(36, '\0');
        const auto start = std::chrono::steady_clock::now();
        const ParseError e = parse_error(data, "huge.ply");
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        // Generous: the check is arithmetic on the header and takes microseconds; a reader
        // that allocated or looped over the count would take minutes or fail to allocate.
        CHECK(seconds < 0.5);
        CHECK(e.line() == 7);
        CHECK(contains(e.what(), "declares 1000000000000 'face' elements"));
    }
}

TEST_CASE("read_mesh_memory: face index out of range or negative", "[geometry][mesh_io]") {
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
    const ParseError e = parse_error(kTriangleHeader + vertices + "3 0 1 3\n", "r.ply");
    CHECK(e.line() == 13);
    CHECK(e.column() == 7);
    CHECK(std::string(e.what()) ==
          "face 0 of 1: vertex index 3 out of range (the file has 3 vertices)");
    const ParseError n = parse_error(kTriangleHeader + vertices + "3 0 -1 2\n", "n.ply");
    CHECK(n.column() == 5);
    CHECK(std::string(n.what()) == "face 0 of 1: negative vertex index -1");

    // Binary: the message carries the byte offset of the index.
    Mesh m = tetrahedron();
    m.faces[2] = {{0, 3, 2}};
    std::string bin = to_ply(m, true);
    const std::size_t body = bin.find("end_header\n") + 11;
    const std::size_t at = body + 4 * 24 + 2 * 13 + 1 + 4;  // face 2, second index
    std::string minus_one;
    put(minus_one, std::int32_t{-1}, false);
    bin.replace(at, 4, minus_one);
    const ParseError b = parse_error(bin, "b.ply");
    CHECK(std::string(b.what()) ==
          "face 2 of 4 (byte " + std::to_string(at) + "): negative vertex index -1");
}

TEST_CASE("read_mesh_memory: NaN and inf coordinates name the vertex", "[geometry][mesh_io]") {
    const ParseError e =
        parse_error(kTriangleHeader + std::string("0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), "n.ply");
    CHECK(e.line() == 11);
    CHECK(e.column() == 3);
    CHECK(std::string(e.what()) == "vertex 1 of 3: non-finite coordinate y = nan");
    const ParseError i =
        parse_error(kTriangleHeader + std::string("0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n"), "i.ply");
    CHECK(contains(i.what(), "vertex 2 of 3: non-finite coordinate z = -inf"));

    Mesh m = tetrahedron(0.5);
    std::string bin = to_ply(m, true);
    const std::size_t body = bin.find("end_header\n") + 11;
    std::string nan;
    put(nan, std::numeric_limits<float>::quiet_NaN(), false);
    bin.replace(body + 12 * 2 + 4, 4, nan);  // vertex 2, y
    const ParseError b = parse_error(bin, "b.ply");
    CHECK(contains(b.what(), "vertex 2 of 4 (byte "));
    CHECK(contains(b.what(), "non-finite coordinate y = nan"));
}

TEST_CASE("read_mesh_memory: malformed PLY headers", "[geometry][mesh_io]") {
    SECTION("missing magic") {
        const ParseError e = parse_error("PLY\nformat ascii 1.0\n", "m.ply");
        CHECK(e.line() == 1);
        CHECK(contains(e.what(), "not a PLY file"));
    }
    SECTION("missing end_header at end of file") {
        std::string data = kTriangleHeader;
        data.erase(data.find("end_header\n"));
        const ParseError e = parse_error(data, "e.ply");
        CHECK(contains(e.what(), "'end_header' is missing"));
    }
    SECTION("missing end_header before the body") {
        std::string data = kTriangleHeader;
        data.erase(data.find("end_header\n"));
        data += "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        const ParseError e = parse_error(data, "e.ply");
        CHECK(e.line() == 9);
        CHECK(contains(e.what(), "is 'end_header' missing?"));
    }
    SECTION("unknown format") {
        std::string data = kTriangleHeader;
        data.replace(data.find("ascii"), 5, "binary_middle_endian");
        const ParseError e = parse_error(data, "f.ply");
        CHECK(e.line() == 2);
        CHECK(e.column() == 8);
        CHECK(contains(e.what(), "unknown PLY format 'binary_middle_endian'"));
    }
    SECTION("list property with a float count type") {
        std::string data = kTriangleHeader;
        data.replace(data.find("list uchar"), 10, "list float");
        const ParseError e = parse_error(data, "l.ply");
        CHECK(e.line() == 8);
        CHECK(e.column() == 15);
        CHECK(contains(e.what(), "count type float, which is not an integer type"));
    }
    SECTION("unknown property type") {
        std::string data = kTriangleHeader;
        data.replace(data.find("float y"), 7, "real y");
        const ParseError e = parse_error(data, "t.ply");
        CHECK(e.line() == 5);
        CHECK(e.column() == 10);
    }
    SECTION("missing z") {
        std::string data = kTriangleHeader;
        data.erase(data.find("property float z\n"), 17);
        const ParseError e = parse_error(data, "z.ply");
        CHECK(e.line() == 3);
        CHECK(contains(e.what(), "no 'z' property"));
    }
    SECTION("point cloud without faces") {
        const std::string data =
            "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n" +
            std::string(12, '\0');
        const ParseError e = parse_error(data, "cloud.ply");
        CHECK(contains(e.what(), "has no faces"));
    }
    SECTION("a polygon with two vertices") {
        const ParseError e =
            parse_error(kTriangleHeader + std::string("0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), "p.ply");
        CHECK(e.line() == 13);
        CHECK(contains(e.what(), "polygon with 2 vertices"));
    }
    SECTION("a word where a number belongs") {
        const ParseError e =
            parse_error(kTriangleHeader + std::string("0 0 0\n1 0 zero\n"), "w.ply");
        CHECK(e.line() == 11);
        CHECK(e.column() == 5);
        CHECK(contains(e.what(), "expected a number for 'z', got 'zero'"));
    }
}

// More data than the header declares means its counts are wrong: reading only what it
// declares would drop faces without a word.
TEST_CASE("read_mesh_memory: data after the declared PLY elements is an error",
          "[geometry][mesh_io]") {
    const Mesh m = tetrahedron();
    SECTION("binary: how many bytes, from where") {
        const std::string ply = to_ply(m, true);
        const ParseError e = parse_error(ply + "garbage", "g.ply");
        CHECK(contains(e.what(), "7 bytes after the last declared element (from byte " +
                                     std::to_string(ply.size()) + ")"));
        CHECK(contains(e.what(), "(4 vertex, 4 face)"));
    }
    SECTION("ASCII: a face more than declared, at its line and column") {
        const ParseError e = parse_error(to_ply(m, false) + "3 0 1 2\n", "g.ply");
        CHECK(e.line() == 18);  // 9 header lines, 4 vertices, 4 faces
        CHECK(e.column() == 1);
        CHECK(contains(e.what(), "'3' after the last declared element"));
    }
    SECTION("a final line break or blanks are not data") {
        CHECK(read_mesh_memory(to_ply(m, true) + "\n", "g.ply").soup.positions == m.positions);
        CHECK(read_mesh_memory(to_ply(m, false) + "\n \r\n", "g.ply").soup.positions ==
              m.positions);
    }
}

// ---- OFF, OBJ, STL -----------------------------------------------------------------------

TEST_CASE("read_mesh_file: reads a written file; errors for missing files and extensions",
          "[geometry][mesh_io]") {
    const Mesh m = tetrahedron();
    const std::string path = "/tmp/geotex_test_mesh_io_" + std::to_string(::getpid()) + ".ply";
    {
        std::ofstream out(path, std::ios::binary);
        write_ply(out, m, {});
    }
    const MeshFile f = read_mesh_file(path);
    std::remove(path.c_str());
    CHECK(f.soup.positions == m.positions);
    CHECK(polygons(f.soup) == polygons(m));

    REQUIRE_THROWS_AS(read_mesh_file("/nonexistent/dir/mesh.ply"), IoError);
    try {
        read_mesh_memory("", "points.xyz");
        FAIL("no exception for .xyz");
    } catch (const InvalidInput& e) {
        CHECK(std::string(e.what()) ==
              "unknown mesh extension '.xyz' (expected .ply, .off, .obj or .stl)");
    }
    REQUIRE_THROWS_AS(read_mesh_file("/tmp/mesh.xyz"), InvalidInput);
}

TEST_CASE("read_mesh_memory: OBJ and OFF may start with a UTF-8 byte order mark",
          "[geometry][mesh_io]") {
    const std::string bom = "\xEF\xBB\xBF";
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    for (const auto& [text, name] : {std::pair{obj, "t.obj"}, std::pair{off, "t.off"}}) {
        const MeshFile plain = read_mesh_memory(text, name);
        const MeshFile marked = read_mesh_memory(bom + text, name);
        CHECK(marked.soup.positions == plain.soup.positions);
        CHECK(marked.soup.face_offsets == plain.soup.face_offsets);
        CHECK(marked.soup.face_indices == plain.soup.face_indices);
    }
    // Only at the start: elsewhere it is what it is, a word the reader does not know, on
    // line 2 column 1 (columns on line 1 would count from after a leading mark).
    CHECK_THROWS_AS(read_mesh_memory("v 0 0 0\n" + bom + "v 1 0 0\n", "t.obj"), ParseError);
}
