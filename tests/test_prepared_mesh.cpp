// The repaired mesh of a tiled run on disk (pipeline/prepared_mesh.hpp, `--pass mesh`): read
// back bit for bit with the repair's report and notes, and refused, saying why, when it is
// another run's, truncated, padded, or holds an index or a coordinate no mesh has; likewise
// its extent, which the mesh pass leaves beside it for the join.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>

#include "common/errors.hpp"
#include "geometry/mesh_repair.hpp"
#include "pipeline/prepared_mesh.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;
using geotex::test::make_sphere;

namespace {

// A sphere with one face given twice and one flipped, so that the repair removes, flips and
// notes something.
PreparedMesh prepared_sphere() {
    const Mesh sphere = make_sphere(1.5, 2);
    PolygonSoup soup;
    soup.positions = sphere.positions;
    for (std::size_t f = 0; f < sphere.faces.size(); ++f) {
        auto face = sphere.faces[f];
        if (f == 7) std::swap(face[1], face[2]);
        soup.face_indices.insert(soup.face_indices.end(), face.begin(), face.end());
        soup.face_offsets.push_back(static_cast<int>(soup.face_indices.size()));
    }
    const auto& again = sphere.faces[3];
    soup.face_indices.insert(soup.face_indices.end(), again.begin(), again.end());
    soup.face_offsets.push_back(static_cast<int>(soup.face_indices.size()));
    return {repair_soup(soup), "PLY"};
}

std::string bytes_of(const std::string& key, const PreparedMesh& mesh) {
    std::ostringstream out;
    write_prepared_mesh(out, key, mesh);
    return out.str();
}

PreparedMesh read_back(const std::string& bytes, const std::string& key) {
    std::istringstream in(bytes);
    return read_prepared_mesh(in, key);
}

}  // namespace

TEST_CASE("a prepared mesh reads back bit for bit with the repair's report and notes",
          "[pipeline][tiles]") {
    const PreparedMesh mesh = prepared_sphere();
    REQUIRE(mesh.repaired.report.num_duplicate_faces_removed == 1);
    REQUIRE(mesh.repaired.report.num_faces_flipped == 1);
    REQUIRE(!mesh.repaired.diagnostics.empty());
    const PreparedMesh back = read_back(bytes_of("k1", mesh), "k1");
    // Vector equality of doubles is bit equality here: no coordinate is NaN or -0.
    CHECK(back.repaired.mesh.positions == mesh.repaired.mesh.positions);
    CHECK(back.repaired.mesh.faces == mesh.repaired.mesh.faces);
    CHECK(back.format == "PLY");
    const MeshRepairReport& a = back.repaired.report;
    const MeshRepairReport& b = mesh.repaired.report;
    CHECK(std::memcmp(&a, &b, sizeof a) == 0);  // a struct of ints, no padding
    REQUIRE(back.repaired.diagnostics.size() == mesh.repaired.diagnostics.size());
    for (std::size_t i = 0; i < back.repaired.diagnostics.size(); ++i) {
        CHECK(back.repaired.diagnostics[i].stage == mesh.repaired.diagnostics[i].stage);
        CHECK(back.repaired.diagnostics[i].message == mesh.repaired.diagnostics[i].message);
    }
    // The file is the header and the arrays, nothing else: 24 bytes a vertex, 12 a face.
    const std::string bytes = bytes_of("k1", mesh);
    CHECK(bytes.size() - test::binary_arrays_start(bytes) ==
          24 * mesh.repaired.mesh.positions.size() + 12 * mesh.repaired.mesh.faces.size());
}

TEST_CASE("a prepared mesh is little-endian whatever the machine", "[pipeline][tiles]") {
    PreparedMesh mesh;
    mesh.repaired.mesh.positions = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
    mesh.repaired.mesh.faces = {{0, 1, 2}};
    const std::string bytes = bytes_of("k", mesh);
    const std::size_t start = test::binary_arrays_start(bytes);
    // 1.0 is 0x3FF0000000000000: its last two bytes, little-endian, are F0 3F.
    CHECK(static_cast<unsigned char>(bytes[start + 6]) == 0xF0);
    CHECK(static_cast<unsigned char>(bytes[start + 7]) == 0x3F);
    // The face (0, 1, 2): index 1 is the bytes 01 00 00 00 after the first index.
    const std::size_t faces = start + 9 * 8;
    CHECK(bytes.substr(faces, 12) == std::string("\0\0\0\0\1\0\0\0\2\0\0\0", 12));
}

TEST_CASE("a prepared mesh of another run or a damaged one is refused, saying why",
          "[pipeline][tiles]") {
    const PreparedMesh mesh = prepared_sphere();
    const std::string good = bytes_of("k1", mesh);
    const std::size_t start = test::binary_arrays_start(good);
    auto refused = [](const std::string& bytes, const std::string& key) {
        try {
            read_back(bytes, key);
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK_THAT(refused(good, "k2"), Catch::Contains("the prepared mesh of another run"));
    CHECK_THAT(refused("", "k1"), Catch::Contains("not a geotex prepared mesh"));
    CHECK_THAT(refused("ply\nformat ascii 1.0\n", "k1"),
               Catch::Contains("not a geotex prepared mesh"));
    CHECK_THAT(refused(good.substr(0, 25), "k1"), Catch::Contains("ends in its header"));
    CHECK_THAT(refused(good.substr(0, start - 3), "k1"), Catch::Contains("ends in its header"));
    CHECK_THAT(refused(good.substr(0, good.size() - 1), "k1"),
               Catch::Contains("ends inside its arrays"));
    CHECK_THAT(refused(good + "x", "k1"), Catch::Contains("bytes past the end"));
    std::string garbled = good;
    garbled[31] = '\xff';  // inside the CBOR header
    CHECK_THAT(refused(garbled, "k1"), Catch::Contains("damaged"));
    std::string long_header = good;
    long_header[28] = '\x7f';  // a header length of about 2^62 bytes
    CHECK_THAT(refused(long_header, "k1"), Catch::Contains("header's length is wrong"));
    // The last face's last index set past the vertices.
    std::string index = good;
    index[good.size() - 1] = '\x7f';
    CHECK_THAT(refused(index, "k1"), Catch::Contains("names a vertex past the last"));
    // The first coordinate made NaN (exponent all ones, a mantissa bit set).
    std::string nan = good;
    const double q = std::numeric_limits<double>::quiet_NaN();
    std::uint64_t bits = 0;
    std::memcpy(&bits, &q, 8);
    for (int k = 0; k < 8; ++k) nan[start + k] = static_cast<char>(bits >> (8 * k));
    CHECK_THAT(refused(nan, "k1"), Catch::Contains("vertex 0 has a coordinate that is not finite"));
}

TEST_CASE("a prepared mesh's outline holds the positions, its faces read a block at a time",
          "[pipeline][tiles]") {
    const PreparedMesh mesh = prepared_sphere();
    const Mesh& m = mesh.repaired.mesh;
    const std::string good = bytes_of("k1", mesh);
    std::istringstream in(good);
    PreparedOutline outline = read_prepared_outline(in, "k1");
    CHECK(outline.mesh.repaired.mesh.positions == m.positions);
    CHECK(outline.mesh.repaired.mesh.faces.empty());
    CHECK(outline.mesh.repaired.report.num_faces_flipped == mesh.repaired.report.num_faces_flipped);
    CHECK(outline.num_vertices == m.positions.size());
    REQUIRE(outline.num_faces == m.faces.size());
    // The positions moved out, as the join moves them: the faces still read.
    const Mesh positions = std::move(outline.mesh.repaired.mesh);
    std::vector<std::array<int, 3>> faces, block;
    for (std::size_t first = 0; first < outline.num_faces; first += 17) {
        read_prepared_faces(in, outline, first, std::min<std::size_t>(17, m.faces.size() - first),
                            block);
        faces.insert(faces.end(), block.begin(), block.end());
    }
    CHECK(faces == m.faces);
    read_prepared_faces(in, outline, 5, 1, block);  // back to an earlier face
    CHECK(block == std::vector<std::array<int, 3>>{m.faces[5]});
    CHECK_THROWS_WITH(read_prepared_faces(in, outline, outline.num_faces - 1, 2, block),
                      Catch::Contains("past the last face"));
    // A damaged index is found when its face is read, named by its index in the mesh.
    std::string index = good;
    index[good.size() - 1] = '\x7f';
    std::istringstream damaged(index);
    const PreparedOutline damaged_outline = read_prepared_outline(damaged, "k1");
    CHECK_NOTHROW(read_prepared_faces(damaged, damaged_outline, 0, 3, block));
    CHECK_THROWS_WITH(
        read_prepared_faces(damaged, damaged_outline, outline.num_faces - 2, 2, block),
        Catch::Contains("face " + std::to_string(outline.num_faces - 1) +
                        " names a vertex past the last"));
}

TEST_CASE(
    "a mesh's extent written beside it reads back bit for bit, and another run's or a "
    "damaged one is refused",
    "[pipeline][tiles]") {
    const Mesh sphere = make_sphere(1.5, 2);
    const MeshMetrics extent = make_mesh_extent(sphere);
    REQUIRE(extent.mean_edge_length > 0);
    std::ostringstream out;
    write_mesh_extent(out, "k1", extent);
    const std::string good = out.str();
    const auto read = [](const std::string& bytes, const std::string& key) {
        std::istringstream in(bytes);
        return read_mesh_extent(in, key);
    };
    const MeshMetrics back = read(good, "k1");
    for (int k = 0; k < 3; ++k) {
        CHECK(test::same_bits(back.bbox_min[k], extent.bbox_min[k]));
        CHECK(test::same_bits(back.bbox_max[k], extent.bbox_max[k]));
    }
    CHECK(test::same_bits(back.largest_side, extent.largest_side));
    CHECK(test::same_bits(back.mean_edge_length, extent.mean_edge_length));
    CHECK(back.num_vertices == sphere.num_vertices());
    CHECK(back.num_faces == sphere.num_faces());
    auto refused = [&](const std::string& bytes, const std::string& key) {
        try {
            read(bytes, key);
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK_THAT(refused(good, "k2"), Catch::Contains("the mesh extent of another run"));
    CHECK_THAT(refused("geotex prepared mesh\n", "k1"),
               Catch::Contains("not a geotex mesh extent"));
    CHECK_THAT(refused(good.substr(0, good.size() - 1), "k1"),
               Catch::Contains("ends in its header"));
    CHECK_THAT(refused(good + "x", "k1"), Catch::Contains("bytes past the end"));
    MeshMetrics infinite = extent;
    infinite.mean_edge_length = std::numeric_limits<double>::infinity();
    std::ostringstream bad;
    write_mesh_extent(bad, "k1", infinite);
    CHECK_THAT(refused(bad.str(), "k1"), Catch::Contains("a number is not finite"));
}
