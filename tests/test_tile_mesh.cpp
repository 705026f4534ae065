// A tile's mesh for the first depth pass on disk (pipeline/tile_mesh.hpp, made by `--pass
// mesh`): read back bit for bit, giving the depth part that the job holding the whole mesh
// gives, and refused, saying why, when it is another run's or tile's, or damaged.

#include <catch2/catch.hpp>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/errors.hpp"
#include "geometry/tile_alone.hpp"
#include "pipeline/tile_mesh.hpp"
#include "tests/fixtures.hpp"
#include "tests/tile_test_support.hpp"

using namespace geotex;
using test::same_bits;
using tile_test::depth_parts;
using tile_test::fast_params;
using tile_test::same_depths;

namespace {

std::string bytes_of(const std::string& key, const DepthTile& tile) {
    std::ostringstream out;
    write_tile_mesh(out, key, tile);
    return out.str();
}

DepthTile read_back(const std::string& bytes, const std::string& key, int tile) {
    std::istringstream in(bytes);
    return read_tile_mesh(in, key, tile);
}

std::string refused(const std::string& bytes, const std::string& key, int tile) {
    try {
        read_back(bytes, key, tile);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "(read)";
}

}  // namespace

TEST_CASE("a tile's mesh read back gives the depth part of the job that holds the whole mesh",
          "[tiles]") {
    const Mesh m = test::half_engraved_sphere(6);
    const SegmentationParams p = fast_params();
    const TiledSegmentation run(m, p, 4);
    int sampled = 0;
    for (int b = 0; b < run.num_tiles(); ++b) {
        const DepthTile made = run.depth_tile(b);
        const DepthTile tile = read_back(bytes_of("k", made), "k", b);
        CHECK(tile.tile == b);
        CHECK(tile.boxes.count == made.boxes.count);
        CHECK(tile.boxes.size() == 4);
        for (int k = 0; k < 3; ++k) {
            CHECK(same_bits(tile.boxes.lo[k], made.boxes.lo[k]));
            CHECK(same_bits(tile.boxes.hi[k], made.boxes.hi[k]));
        }
        CHECK(tile.mesh_vertices == m.num_vertices());
        CHECK(same_bits(tile.radius, made.radius));
        CHECK(same_bits(tile.halo, made.halo));
        CHECK(tile.halo == kTileMeshHaloRadii * made.radius);
        CHECK(tile.mesh.mesh.faces == made.mesh.mesh.faces);
        REQUIRE(tile.mesh.mesh.positions.size() == made.mesh.mesh.positions.size());
        for (std::size_t v = 0; v < tile.mesh.mesh.positions.size(); ++v)
            for (int k = 0; k < 3; ++k)
                CHECK(same_bits(tile.mesh.mesh.positions[v][k], made.mesh.mesh.positions[v][k]));
        CHECK(tile.mesh.vertex == made.mesh.vertex);
        CHECK(tile.mesh.face == made.mesh.face);
        CHECK(tile.mesh.owned_vertex == made.mesh.owned_vertex);
        CHECK(tile.mesh.owned_face == made.mesh.owned_face);
        CHECK(tile.mesh.complete_vertex == made.mesh.complete_vertex);
        CHECK(tile.sampling.fast == made.sampling.fast);
        CHECK(tile.sampling.grid == made.sampling.grid);
        for (int k = 0; k < 3; ++k)
            CHECK(same_bits(tile.sampling.origin[k], made.sampling.origin[k]));
        CHECK(tile.components.component == made.components.component);
        CHECK(tile.components.num_components == made.components.num_components);
        for (char f : tile.sampling.fast) sampled += f;

        // The part from the tile alone is the part of the run that holds the whole mesh.
        const TilePart alone = first_depth_part(tile, p);
        const TilePart whole = run.run_tile(b);
        CHECK(alone.pass == TilePass::Depth);
        CHECK(alone.tile == b);
        CHECK(alone.vertices == whole.vertices);
        CHECK(alone.depths.size() == 2);  // both orientations: rims are removed
        CHECK(same_depths(alone, whole));
        CHECK(alone.interpolated == whole.interpolated);
        CHECK(alone.samples == whole.samples);
    }
    CHECK(sampled > 0);  // the fast mode sampled some discs: the flags were carried
}

TEST_CASE("a run that reads the faces a block at a time cuts the tiles of the run that holds them",
          "[tiles]") {
    // A second piece, apart, and a vertex no face uses: the components and the sampling are
    // found over the blocks too.
    Mesh m = test::half_engraved_sphere(6);
    const Mesh piece = test::make_sphere(0.2, 2);
    const int offset = m.num_vertices();
    for (const auto& x : piece.positions) m.positions.push_back(x + Eigen::Vector3d(3, 0, 0));
    for (const auto& f : piece.faces)
        m.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
    m.positions.emplace_back(0, 3, 0);
    const SegmentationParams p = fast_params();
    const TiledSegmentation held(m, p, 4);
    Mesh vertices;
    vertices.positions = m.positions;
    std::size_t read = 0;
    MeshOutline outline{vertices.positions, make_mesh_extent(m), {}, {}, {}};
    outline.faces = [&](const std::vector<int>& ids) {
        std::vector<std::array<int, 3>> out;
        for (int f : ids) out.push_back(m.faces[f]);
        return out;
    };
    const TiledSegmentation without_blocks(outline, p, 4);
    CHECK_THROWS_AS(without_blocks.depth_tile(0), std::invalid_argument);
    const FaceBlockReader in_memory = face_reader(m.faces);
    outline.blocks = [&](std::size_t first, std::size_t n, std::vector<std::array<int, 3>>& out) {
        in_memory(first, n, out);
        read += n;
    };
    const TiledSegmentation outlined(outline, p, 4);
    for (int b = 0; b < 4; ++b) {
        INFO("tile " << b);
        CHECK(bytes_of("k", outlined.depth_tile(b)) == bytes_of("k", held.depth_tile(b)));
    }
    // The faces are read for the components, the sampling, the tiler's chunks and what may be
    // each tile's.
    CHECK(read >= 3 * m.faces.size());
    CHECK(read <= 7 * m.faces.size());
    const test::TempDir dir("spooled");
    // The same cut from the vertices numbered by their places in the order of space, as the
    // mesh job cuts them: the choices at a tile's vertices are then read by place, not by id.
    const SpaceOrderedPositions near(vertices.positions, dir.path().string());
    ScratchFile placed_faces =
        faces_in_places(in_memory, m.faces.size(), near.places(), dir.path().string());
    outline.placed = {near.copy(), face_reader(placed_faces), near.ids()};
    const TiledSegmentation in_places(outline, p, 4);
    for (int b = 0; b < 4; ++b) {
        INFO("tile " << b);
        const std::string bytes = bytes_of("k", held.depth_tile(b));
        // Written as its faces are read back from a scratch file, never held.
        for (const TiledSegmentation* run : {&outlined, &in_places}) {
            std::ostringstream spooled;
            run->spool_depth_tile(b, dir.path().string(),
                                  [&](const DepthTile& numbers, const DepthTileRows& rows) {
                                      CHECK(numbers.mesh.vertex.empty());
                                      write_tile_mesh(spooled, "k", numbers, rows);
                                  });
            CHECK(spooled.str() == bytes);
        }
    }
    CHECK_THROWS_AS(held.spool_depth_tile(0, dir.path().string(),
                                          [](const DepthTile&, const DepthTileRows&) {}),
                    std::invalid_argument);
    CHECK_THROWS_WITH(outlined.spool_depth_tile(4, dir.path().string(),
                                                [](const DepthTile&, const DepthTileRows&) {}),
                      Catch::Contains("tile 5 is not in 1 to 4"));
}

TEST_CASE("a tile's mesh of another run or tile, or a damaged one, is refused, saying why",
          "[tiles]") {
    const Mesh m = test::make_sphere(1.5, 3);
    const TiledSegmentation run(m, fast_params(), 4);
    const DepthTile tile = run.depth_tile(1);
    const std::string good = bytes_of("k1", tile);
    REQUIRE(refused(good, "k1", 1) == "(read)");
    const std::size_t nv = tile.mesh.mesh.positions.size(), nf = tile.mesh.mesh.faces.size();
    const std::size_t start = test::binary_arrays_start(good);
    CHECK(good.size() == start + 33 * nv + 17 * nf);

    CHECK_THAT(refused(good, "k2", 1), Catch::Contains("the tile mesh of another run"));
    CHECK_THAT(refused(good, "k1", 2), Catch::Contains("the mesh of tile 2, not of tile 3"));
    CHECK_THAT(refused("", "k1", 1), Catch::Contains("not a geotex tile mesh"));
    CHECK_THAT(refused(good.substr(0, 20), "k1", 1), Catch::Contains("ends in its header"));
    CHECK_THAT(refused(good.substr(0, good.size() - 1), "k1", 1),
               Catch::Contains("ends inside its arrays"));
    CHECK_THAT(refused(good + "x", "k1", 1), Catch::Contains("bytes past the end"));

    // Each array's bytes spoiled in turn.
    const auto spoiled = [&](std::size_t at, const std::string& bytes) {
        std::string s = good;
        s.replace(at, bytes.size(), bytes);
        return refused(s, "k1", 1);
    };
    const std::string nan_bits = [] {
        const double x = std::numeric_limits<double>::quiet_NaN();
        return std::string(reinterpret_cast<const char*>(&x), 8);
    }();
    CHECK_THAT(spoiled(start + 8, nan_bits), Catch::Contains("vertex 0 has a coordinate"));
    const std::size_t ids = start + 24 * nv;
    CHECK_THAT(spoiled(ids + 4, std::string(4, '\0')),
               Catch::Contains("the ids of its vertices do not ascend"));
    const std::size_t flags = ids + 4 * nv;
    CHECK_THAT(spoiled(flags + 2, "\x08"), Catch::Contains("vertex 2's flags are unknown"));
    const std::size_t components = flags + nv;
    CHECK_THAT(spoiled(components + 4, std::string("\xff\xff\x00\x00", 4)),
               Catch::Contains("vertex 1's component is out of range"));
    const std::size_t faces = components + 4 * nv;
    CHECK_THAT(spoiled(faces + 12, std::string("\xff\xff\xff\x00", 4)),
               Catch::Contains("face 1 names a vertex past the last"));
    const std::size_t face_ids = faces + 12 * nf;
    CHECK_THAT(spoiled(face_ids + 4 * (nf - 1), std::string(4, '\0')),
               Catch::Contains("the ids of its faces do not ascend"));
    CHECK_THAT(spoiled(face_ids + 4 * nf, "\x02"), Catch::Contains("face 0's flags are unknown"));
}

TEST_CASE("a depth part is refused a tile whose arrays do not fit its vertices", "[tiles]") {
    const Mesh m = test::make_sphere(1.5, 3);
    const SegmentationParams p = fast_params();
    const TiledSegmentation run(m, p, 4);
    DepthTile tile = run.depth_tile(0);
    tile.sampling.fast.pop_back();
    CHECK_THROWS_WITH(first_depth_part(tile, p), Catch::Contains("sampling or components"));
    tile = run.depth_tile(0);
    tile.tile = 4;
    CHECK_THROWS_WITH(first_depth_part(tile, p), Catch::Contains("not one of the run's tiles"));
    tile = run.depth_tile(0);
    tile.components.component[0] = tile.components.num_components;
    CHECK_THROWS_WITH(first_depth_part(tile, p), Catch::Contains("component is out of range"));
    tile = run.depth_tile(0);
    tile.halo = 5 * tile.radius;
    CHECK_THROWS_WITH(first_depth_part(tile, p), Catch::Contains("halo is narrower"));
    CHECK_THROWS_WITH(run.depth_tile(4), Catch::Contains("tile 5 is not in 1 to 4"));
}
