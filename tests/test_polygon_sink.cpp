// The readers with a PolygonSink (mesh_io.hpp): the polygons and positions they keep in the
// soup without one go to the sink instead (an STL file's positions excepted), in file order, a
// block at a time, each polygon whole, and a bad file gets the same error either way.
#include <catch2/catch.hpp>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "tests/fixtures.hpp"
#include "tests/mesh_io_helpers.hpp"

using namespace geotex;
using namespace geotex::test;

namespace {

// Enough polygons that their corners (3.5 a polygon) fill more than one of the readers' blocks
// of 2^20 corners, and vertices for more than one of their blocks of 2^18 positions.
constexpr int kMany = 400'000;
constexpr int kManyVertices = 300'000;
constexpr std::size_t kBlockPositions = std::size_t{1} << 18;

// Polygon i of the files below: a triangle when i is even, a quad when it is odd.
std::vector<int> corners_of(int i) {
    if (i % 2 == 0) return {0, 1, 2};
    return {0, 2, 3, 1};
}

const double kCorners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

// The vertices of the files below but STL: the four corners, then points no polygon uses.
std::vector<std::array<double, 3>> many_vertices() {
    std::vector<std::array<double, 3>> out;
    for (const auto& p : kCorners) out.push_back({p[0], p[1], p[2]});
    for (int i = 4; i < kManyVertices; ++i) out.push_back({0.25 * i, 2.0, -0.5});
    return out;
}

// A vertex's line in a text format: its coordinates after `prefix`.
std::string corner_line(const std::array<double, 3>& p, const std::string& prefix = "") {
    return prefix + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) +
           "\n";
}

// Polygon i's line in a text format: OBJ's "f" and corners from 1, or OFF's and PLY's count
// and corners from 0.
std::string polygon_line(int i, bool obj) {
    const std::vector<int> c = corners_of(i);
    std::string line = obj ? "f" : std::to_string(c.size());
    for (const int v : c) line += " " + std::to_string(obj ? v + 1 : v);
    return line + "\n";
}

std::string many_obj() {
    std::string s;
    for (const auto& p : many_vertices()) s += corner_line(p, "v ");
    for (int i = 0; i < kMany; ++i) s += polygon_line(i, true);
    return s;
}

std::string many_off_ascii() {
    std::string s = "OFF\n" + std::to_string(kManyVertices) + " " + std::to_string(kMany) + " 0\n";
    for (const auto& p : many_vertices()) s += corner_line(p);
    for (int i = 0; i < kMany; ++i) s += polygon_line(i, false);
    return s;
}

std::string many_off_binary() {
    std::string s = "OFF BINARY\n";
    for (const int count : {kManyVertices, kMany, 0}) put<std::int32_t>(s, count, true);
    for (const auto& p : many_vertices())
        for (const double x : p) put<float>(s, static_cast<float>(x), true);
    for (int i = 0; i < kMany; ++i) {
        const std::vector<int> c = corners_of(i);
        put<std::int32_t>(s, static_cast<std::int32_t>(c.size()), true);
        for (const int v : c) put<std::int32_t>(s, v, true);
    }
    return s;
}

std::string many_ply(const std::string& format) {
    std::string s =
        "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(kManyVertices) +
        "\nproperty float x\nproperty float y\n"
        "property float z\nelement face " +
        std::to_string(kMany) + "\nproperty list uchar int vertex_indices\nend_header\n";
    const bool big = format == "binary_big_endian";
    for (const auto& p : many_vertices()) {
        if (format == "ascii") {
            s += corner_line(p);
        } else {
            for (const double x : p) put<float>(s, static_cast<float>(x), big);
        }
    }
    for (int i = 0; i < kMany; ++i) {
        if (format == "ascii") {
            s += polygon_line(i, false);
            continue;
        }
        const std::vector<int> c = corners_of(i);
        s += static_cast<char>(c.size());
        for (const int v : c) put<std::int32_t>(s, v, big);
    }
    return s;
}

// STL holds triangles only: the quads' place takes a second triangle.
std::string many_stl_binary() {
    std::string s(80, ' ');
    put<std::uint32_t>(s, kMany, false);
    for (int i = 0; i < kMany; ++i) {
        for (int k = 0; k < 3; ++k) put<float>(s, 0.0F, false);  // the normal, ignored
        const std::vector<int> c =
            i % 2 == 0 ? std::vector<int>{0, 1, 2} : std::vector<int>{0, 2, 3};
        for (const int v : c)
            for (const double x : kCorners[v]) put<float>(s, static_cast<float>(x), false);
        s += std::string(2, '\0');
    }
    return s;
}

// What a sink was given.
struct Blocks {
    std::vector<PolygonSoup> blocks;
    PolygonSink sink() {
        return [this](const PolygonSoup& b) { blocks.push_back(b); };
    }
    // Every block's positions, in order.
    std::vector<Eigen::Vector3d> positions_given() const {
        std::vector<Eigen::Vector3d> out;
        for (const PolygonSoup& b : blocks)
            out.insert(out.end(), b.positions.begin(), b.positions.end());
        return out;
    }
    // Every block's polygons, in order.
    std::vector<std::vector<int>> polygons_given() const {
        std::vector<std::vector<int>> out;
        for (const PolygonSoup& b : blocks) {
            const std::vector<std::vector<int>> some = polygons(b);
            out.insert(out.end(), some.begin(), some.end());
        }
        return out;
    }
};

// Reading `data` as `name` with a sink gives the sink the polygons and positions it gives the
// soup without (an STL file's positions stay in the soup).
void require_same_through_sink(const std::string& data, const std::string& name) {
    INFO(name);
    const MeshFile held = read_mesh_memory(data, name);
    Blocks given;
    const MeshFile file = read_mesh_memory(data, name, given.sink());
    CHECK(file.soup.face_offsets == std::vector<int>{0});
    CHECK(file.soup.face_indices.empty());
    CHECK(file.format == held.format);
    REQUIRE(given.blocks.size() >= 2);
    int with_positions = 0;
    for (const PolygonSoup& b : given.blocks) {
        CHECK(b.positions.size() <= kBlockPositions);
        with_positions += b.positions.empty() ? 0 : 1;
        REQUIRE(b.face_offsets.front() == 0);
        CHECK(static_cast<std::size_t>(b.face_offsets.back()) == b.face_indices.size());
    }
    if (file.format == "stl") {
        CHECK(file.soup.positions == held.soup.positions);
        CHECK(with_positions == 0);
    } else {
        CHECK(file.soup.positions.empty());
        CHECK(given.positions_given() == held.soup.positions);
        CHECK(held.soup.positions.size() == static_cast<std::size_t>(kManyVertices));
        CHECK(with_positions >= 2);
    }
    CHECK(given.polygons_given() == polygons(held.soup));
    CHECK(polygons(held.soup).size() == static_cast<std::size_t>(kMany));
}

// Reading the bad `data` as `name` with a sink gives the error `held` that it gives without
// one; returns what the sink had by then.
Blocks require_same_error_through_sink(const std::string& data, const std::string& name,
                                       const std::string& held) {
    Blocks given;
    try {
        read_mesh_memory(data, name, given.sink());
        FAIL("no error with a sink");
    } catch (const ParseError& e) {
        CHECK(e.located() == held);
    }
    return given;
}

}  // namespace

TEST_CASE("polygon sink: every reader gives it the polygons it would hold", "[geometry][mesh_io]") {
    require_same_through_sink(many_obj(), "many.obj");
    require_same_through_sink(many_off_ascii(), "many.off");
    require_same_through_sink(many_off_binary(), "many-binary.off");
    require_same_through_sink(many_ply("ascii"), "many-ascii.ply");
    require_same_through_sink(many_ply("binary_little_endian"), "many-le.ply");
    require_same_through_sink(many_ply("binary_big_endian"), "many-be.ply");
    require_same_through_sink(many_stl_binary(), "many.stl");
}

TEST_CASE("polygon sink: a small file is one block, ASCII STL too", "[geometry][mesh_io]") {
    const std::string stl =
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nendsolid t\n";
    for (const auto& [data, name] : {std::pair<std::string, std::string>{stl, "t.stl"},
                                     {to_ply(tetrahedron(), false), "t.ply"}}) {
        Blocks given;
        const MeshFile file = read_mesh_memory(data, name, given.sink());
        REQUIRE(given.blocks.size() == 1);
        CHECK(given.polygons_given() == polygons(read_mesh_memory(data, name).soup));
        CHECK(file.soup.num_polygons() == 0);
    }
}

TEST_CASE("polygon sink: errors name the same place, past the first block", "[geometry][mesh_io]") {
    // A face past the first block that names a vertex the file lacks: its number counts the
    // polygons the sink has had.
    const std::string past = std::to_string(kManyVertices + 1);
    const std::string obj = many_obj() + "f 1 2 " + past + "\n";
    const std::string held = parse_error(obj, "bad.obj").located();
    CHECK(contains(held, "bad.obj:" + std::to_string(kManyVertices + kMany + 1) + ":"));
    CHECK(contains(held,
                   "face " + std::to_string(kMany) + ": vertex index " + past + " out of range"));
    // The sink had part of the file: its caller drops it.
    CHECK_FALSE(require_same_error_through_sink(obj, "bad.obj", held).blocks.empty());
    // What the sink throws (a full disk) comes out of the reader.
    const PolygonSink full = [](const PolygonSoup&) { throw std::runtime_error("disk full"); };
    CHECK_THROWS_WITH(read_mesh_memory(many_obj(), "many.obj", full), "disk full");
    // A coordinate that is not a number in the last vertex, past the first block of positions.
    const std::string last = corner_line({0.25 * (kManyVertices - 1), 2.0, -0.5});
    for (const auto& [data, name, prefix] :
         {std::tuple<std::string, std::string, std::string>{many_obj(), "nan.obj", "v "},
          {many_ply("ascii"), "nan.ply", ""},
          {many_off_ascii(), "nan.off", ""}}) {
        std::string bad = data;
        const std::size_t at = bad.find(prefix + last);
        REQUIRE(at != std::string::npos);
        bad.replace(at, prefix.size() + last.size(),
                    prefix + std::to_string(0.25 * (kManyVertices - 1)) + " nan -0.5\n");
        const std::string held_nan = parse_error(bad, name).located();
        INFO(held_nan);
        CHECK(contains(held_nan, "vertex " + std::to_string(kManyVertices - 1)));
        CHECK_FALSE(require_same_error_through_sink(bad, name, held_nan).blocks.empty());
    }
}

TEST_CASE("polygon sink: a PLY's face properties are not held with one", "[geometry][mesh_io]") {
    // A segmentation PLY read back: its faces carry scalars, which a reader without a sink keeps
    // (8 bytes a face each) and one with a sink skips, as it skips a vertex's colour.
    const std::vector<FaceAttribute> attrs = {
        {"texel", PlyScalarType::Int32, {3, -1, 7, 0}},
        {"red", PlyScalarType::UInt8, {10, 20, 30, 40}},
    };
    for (const bool binary : {false, true}) {
        INFO((binary ? "binary" : "ascii"));
        const std::string data = to_ply(tetrahedron(), binary, attrs);
        const MeshFile held = read_mesh_memory(data, "seg.ply");
        REQUIRE(held.face_properties.size() == 2);
        CHECK(held.face_properties[0].values == std::vector<double>{3, -1, 7, 0});
        Blocks given;
        const MeshFile file = read_mesh_memory(data, "seg.ply", given.sink());
        CHECK(file.face_properties.empty());
        CHECK(given.positions_given() == held.soup.positions);
        CHECK(given.polygons_given() == polygons(held.soup));
    }
    // A skipped value is still read as a number: a bad one gets the same error either way.
    std::string bad = to_ply(tetrahedron(), false, attrs);
    const std::size_t last = bad.rfind(" 40");
    REQUIRE(last != std::string::npos);
    bad.replace(last, 3, " 4x");
    require_same_error_through_sink(bad, "bad.ply", parse_error(bad, "bad.ply").located());
}

TEST_CASE("read_mesh_file: a file cut short while it is read is an error, not a crash",
          "[geometry][mesh_io]") {
    // read_mesh_file maps the file (geometry/detail/mapped_file.hpp). Another program that cuts
    // it short under the reader would kill the process (SIGBUS) at the next page past the new
    // end; here the sink, called as the reader goes, plays that program.
    const TempDir dir("cut");
    for (const auto& [bytes, name] : {std::pair<std::string, std::string>{many_obj(), "many.obj"},
                                      {many_ply("binary_little_endian"), "many.ply"}}) {
        INFO(name);
        const std::string path = (dir.path() / name).string();
        write_file(path, bytes);
        bool cut = false;
        const PolygonSink cut_it = [&](const PolygonSoup&) {
            if (!cut) std::filesystem::resize_file(path, bytes.size() / 2);
            cut = true;
        };
        try {
            read_mesh_file(path, cut_it);
            FAIL("no error for a file cut short");
        } catch (const IoError& e) {
            // The reader stops at the first page past the new end that it touches, or, reading
            // zeros past the new end within its page, at the new end.
            const std::string located = e.located();
            INFO(located);
            CHECK(located.rfind(path + ": cannot read mesh file past byte ", 0) == 0);
            CHECK(contains(located,
                           " (was it cut short while it was read, or is the disk failing?)"));
            const std::size_t at = std::stoul(located.substr(located.find("past byte ") + 10));
            CHECK(at >= bytes.size() / 2);
            CHECK((at == bytes.size() / 2 || at % 4096 == 0));
        }
        CHECK(cut);
        // The next file read is read whole, and is not taken for cut short.
        write_file(path, bytes);
        const MeshFile again = read_mesh_file(path);
        CHECK(polygons(again.soup) == polygons(read_mesh_memory(bytes, name).soup));
    }
}
