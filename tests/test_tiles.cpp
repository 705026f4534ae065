// Tiles of a mesh (geometry/tiles.hpp): the boxes, what each tile holds and owns, and depth
// maps made tile by tile against the whole mesh's.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>
#include <vector>

#include "common/errors.hpp"
#include "geometry/depth_map.hpp"
#include "geometry/detail/tile_steps.hpp"
#include "geometry/scratch_file.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/smoothed_surface.hpp"
#include "geometry/synth.hpp"
#include "geometry/tiled_segmentation.hpp"
#include "geometry/topology.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

// A box 4 long, 2 wide and 1 high, as the corners of a mesh's bounding box.
Mesh box_corners() {
    Mesh m;
    m.positions = {{0, 0, 0}, {4, 2, 1}, {4, 0, 0}};
    m.faces = {{0, 1, 2}};
    return m;
}

std::vector<DepthMap> whole_depth_maps(const Mesh& mesh, const SmoothingParams& params,
                                       const std::vector<DetailOrientation>& orientations) {
    const MeshTopology t = make_topology(mesh);
    const MeshMetrics mm = make_mesh_metrics(mesh, t);
    const SmoothedSurface s = make_smoothed_surface(mesh, t, mm, params);
    std::vector<DepthMap> maps;
    for (DetailOrientation o : orientations)
        maps.push_back(make_depth_map(mesh, mm.vertex_normal, s, o));
    return maps;
}

// The largest vertex depth difference between two depth maps of one mesh.
double largest_difference(const DepthMap& a, const DepthMap& b) {
    double most = 0;
    for (std::size_t v = 0; v < a.vertex_depth.size(); ++v)
        most = std::max(most, std::abs(a.vertex_depth[v] - b.vertex_depth[v]));
    return most;
}

// Sphere-1 at a low level with half its shapes engraved: both orientations have details.
Mesh engraved_sphere(int level) { return test::half_engraved_sphere(level); }

}  // namespace

TEST_CASE("tile boxes cut the two longest sides into near-square grids", "[tiles]") {
    const Mesh m = box_corners();
    struct Case {
        int count, nx, ny;
    };
    for (const Case c : {Case{1, 1, 1}, Case{4, 2, 2}, Case{9, 3, 3}, Case{6, 3, 2}, Case{7, 7, 1},
                         Case{12, 4, 3}}) {
        const TileBoxes b = make_tile_boxes(m.positions, c.count);
        CHECK(b.size() == c.count);
        CHECK(b.count[0] == c.nx);  // x is the longest side
        CHECK(b.count[1] == c.ny);
        CHECK(b.count[2] == 1);
    }
    const TileBoxes b = make_tile_boxes(m.positions, 4);
    CHECK(b.box_of({0.5, 0.5, 0.5}) == 0);
    CHECK(b.box_of({3.5, 0.5, 0.5}) == 1);
    CHECK(b.box_of({0.5, 1.5, 0.5}) == 2);
    CHECK(b.box_of({4, 2, 1}) == 3);  // the upper corner belongs to the last box
    CHECK(b.box_of({9, 9, 9}) == 3);
    CHECK(b.distance(0, {1, 1, 0.5}) == 0);
    CHECK(b.distance(0, {3, 1, 0.5}) == Approx(1));
    CHECK(b.distance(0, {5, 4, 0.5}) == Approx(std::sqrt(9.0 + 9.0)));
    CHECK_THROWS_AS(make_tile_boxes(m.positions, 0), InvalidInput);
    CHECK_THROWS_AS(make_tile_boxes(PositionSpan{}, 4), InvalidInput);
}

namespace {

// Every field of two tiles.
void require_same_tile(const MeshTile& a, const MeshTile& b) {
    REQUIRE(a.face == b.face);
    REQUIRE(a.vertex == b.vertex);
    REQUIRE(a.owned_face == b.owned_face);
    REQUIRE(a.owned_vertex == b.owned_vertex);
    REQUIRE(a.complete_vertex == b.complete_vertex);
    REQUIRE(a.mesh.faces == b.mesh.faces);
    REQUIRE(a.mesh.positions == b.mesh.positions);
}

// A spooled tile read back whole, block after block as a writer reads it.
MeshTile held_from(const SpooledTile& s) {
    MeshTile t;
    t.vertex = s.vertex();
    for (std::size_t k = 0; k < s.num_vertices(); ++k) {
        t.mesh.positions.push_back(s.position(k));
        t.owned_vertex.push_back(s.owned_vertex(k) ? 1 : 0);
        t.complete_vertex.push_back(s.complete_vertex(k) ? 1 : 0);
    }
    s.for_each_face_block([&](const TileFaceBlock& block) {
        REQUIRE(block.faces.size() == block.ids.size());
        REQUIRE(block.faces.size() == block.owned.size());
        t.mesh.faces.insert(t.mesh.faces.end(), block.faces.begin(), block.faces.end());
        t.face.insert(t.face.end(), block.ids.begin(), block.ids.end());
        t.owned_face.insert(t.owned_face.end(), block.owned.begin(), block.owned.end());
    });
    REQUIRE(t.face.size() == s.num_faces());
    return t;
}

}  // namespace

TEST_CASE("every face and vertex is owned by one tile, and the halo holds what is near",
          "[tiles]") {
    const Mesh m = test::make_grid(30, 3.0, [](double x, double y) { return 0.1 * x * y; });
    const TileBoxes boxes = make_tile_boxes(m.positions, 9);
    const double halo = 0.35;
    std::vector<int> face_owners(m.faces.size(), 0), vertex_owners(m.positions.size(), 0);
    std::vector<int> vertex_box, face_box;
    for (const auto& p : m.positions) vertex_box.push_back(boxes.box_of(p));
    for (const auto& t : m.faces)
        face_box.push_back(
            boxes.box_of((m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0));
    const auto owned_by = [](const std::vector<int>& box, int b) {
        std::vector<char> out;
        for (int x : box) out.push_back(x == b ? 1 : 0);
        return out;
    };
    for (int b = 0; b < boxes.size(); ++b) {
        const MeshTile tile = make_mesh_tile(m, boxes, b, halo);
        // The owners found once give the same tile.
        const std::vector<char> vertex_owned = owned_by(vertex_box, b),
                                face_owned = owned_by(face_box, b);
        require_same_tile(make_mesh_tile(m, boxes, b, halo, {&vertex_owned, &face_owned}), tile);
        REQUIRE(tile.mesh.faces.size() == tile.face.size());
        REQUIRE(tile.mesh.positions.size() == tile.vertex.size());
        CHECK(std::is_sorted(tile.face.begin(), tile.face.end()));
        CHECK(std::is_sorted(tile.vertex.begin(), tile.vertex.end()));
        std::vector<char> in_tile(m.faces.size(), 0);
        for (std::size_t i = 0; i < tile.face.size(); ++i) {
            const int f = tile.face[i];
            in_tile[f] = 1;
            face_owners[f] += tile.owned_face[i];
            for (int k = 0; k < 3; ++k)  // the tile's face is the whole mesh's face
                CHECK(tile.mesh.positions[tile.mesh.faces[i][k]] == m.positions[m.faces[f][k]]);
        }
        for (std::size_t i = 0; i < tile.vertex.size(); ++i)
            vertex_owners[tile.vertex[i]] += tile.owned_vertex[i];
        // Every face with a vertex within the halo of the box is in the tile.
        for (std::size_t f = 0; f < m.faces.size(); ++f) {
            bool near = false;
            for (int v : m.faces[f]) near = near || boxes.distance(b, m.positions[v]) <= halo;
            if (near) CHECK(in_tile[f]);
        }
    }
    CHECK(std::all_of(face_owners.begin(), face_owners.end(), [](int n) { return n == 1; }));
    CHECK(std::all_of(vertex_owners.begin(), vertex_owners.end(), [](int n) { return n == 1; }));
    CHECK_THROWS_AS(make_mesh_tile(m, boxes, 9, halo), InvalidInput);
    CHECK_THROWS_AS(make_mesh_tile(m, boxes, 0, -1), InvalidInput);
    const std::vector<char> vertex_owned = owned_by(vertex_box, 0);
    std::vector<char> short_face = owned_by(face_box, 0);
    short_face.pop_back();
    CHECK_THROWS_AS(make_mesh_tile(m, boxes, 0, halo, {&vertex_owned, &short_face}), InvalidInput);
    CHECK_THROWS_AS(make_mesh_tile(m, boxes, 0, halo, {&vertex_owned, nullptr}), InvalidInput);
}

TEST_CASE("the tilers cut each tile as the scan of the whole mesh does", "[tiles]") {
    // A bumpy grid; the same far from the origin; a flat one (one side of its box is 0); a
    // sphere; and a grid with a few long slivers, whose faces reach far from their centroids.
    std::vector<std::pair<std::string, Mesh>> meshes;
    meshes.emplace_back("grid", test::make_grid(40, 3.0, [](double x, double y) {
                            return 0.2 * std::sin(3 * x) * std::cos(2 * y);
                        }));
    Mesh far = meshes.back().second;
    for (auto& p : far.positions) p += Eigen::Vector3d(1e6, -2e5, 3e4);
    meshes.emplace_back("far", std::move(far));
    meshes.emplace_back("flat", test::make_grid(25, 2.0, [](double, double) { return 0.0; }));
    meshes.emplace_back("sphere", test::make_sphere(1.0, 3));
    Mesh slivers = test::make_grid(30, 3.0, [](double x, double y) { return 0.05 * x * y; });
    const int corner = static_cast<int>(slivers.positions.size()) - 1;
    for (int f = 0; f < static_cast<int>(slivers.faces.size()); f += 97)
        slivers.faces.push_back({slivers.faces[f][0], slivers.faces[f][1], corner});
    meshes.emplace_back("slivers", std::move(slivers));
    const test::TempDir dir("tilers");
    int failed_reads = 0;  // tilers whose read was made to fail in the middle of a tile
    for (const auto& [name, m] : meshes) {
        for (int count : {1, 2, 4, 6, 9, 16, 25}) {
            const TileBoxes boxes = make_tile_boxes(m.positions, count);
            MeshTiler tiler(m, boxes);
            // The faces as a file gives them, a block at a time, in chunks of 1 face to more
            // than the mesh, each face read counted.
            std::size_t read = 0, calls = 0;
            std::size_t fail_at_call = 0;  // when above 0: the read of that number fails
            const FaceBlockReader held = face_reader(m.faces);
            const FaceBlockReader faces = [&](std::size_t first, std::size_t n,
                                              std::vector<std::array<int, 3>>& out) {
                REQUIRE(first + n <= m.faces.size());
                if (++calls == fail_at_call) throw std::runtime_error("read");
                held(first, n, out);
                read += n;
            };
            const std::size_t block = count == 4    ? 1
                                      : count == 9  ? 5
                                      : count == 25 ? kFaceBlock
                                                    : 64;
            StreamTiler streamed(m.positions, faces, m.faces.size(), boxes, block);
            CHECK(read == m.faces.size());  // one pass, for the faces' reach
            // The same cut from the vertices numbered by their places in the order of space,
            // which are not the ids of these meshes (rows of a grid, levels of a sphere).
            const SpaceOrderedPositions near(m.positions, dir.path().string());
            ScratchFile placed_faces =
                faces_in_places(held, m.faces.size(), near.places(), dir.path().string());
            StreamTiler placed(near.copy(), face_reader(placed_faces), m.faces.size(), boxes, block,
                               near.ids());
            const double side = (boxes.hi - boxes.lo).maxCoeff();
            for (double halo : {0.0, 1e-3 * side, 0.05 * side, 0.3 * side, 2.0 * side}) {
                std::size_t read_by_tiles = 0;
                // Backwards, so that a tile follows one that left the scratch elsewhere.
                for (int b = boxes.size() - 1; b >= 0; --b) {
                    INFO(name << ", " << count << " tiles, chunks of " << block << ", halo " << halo
                              << ", tile " << b);
                    const MeshTile whole = make_mesh_tile(m, boxes, b, halo);
                    require_same_tile(tiler.tile(b, halo), whole);
                    read = 0;
                    require_same_tile(streamed.tile(b, halo), whole);
                    CHECK(read <= m.faces.size());  // at most one pass a tile
                    read_by_tiles += read;
                    require_same_tile(placed.tile(b, halo), whole);
                    // Spooled, its faces read back in blocks of 1, 7 or more than the tile's.
                    const std::size_t back = count == 4 ? 1 : count == 9 ? 7 : kFaceBlock;
                    int spooled = 0;
                    for (StreamTiler* t : {&streamed, &placed})
                        t->spool(
                            b, halo, dir.path().string(),
                            [&](const SpooledTile& s) {
                                require_same_tile(held_from(s), whole);
                                ++spooled;
                            },
                            back);
                    CHECK(spooled == 2);
                }
                // Chunks of a few faces of a grid, each near its own tile's box: the tiles of a
                // narrow halo pass over the chunks of the others. (A grid's chunk of 64 faces is
                // a row that crosses every box along it; slivers and a coarse sphere's faces
                // reach across much of a box.)
                if (block <= 5 && halo <= 1e-3 * side && name != "slivers" && name != "sphere")
                    CHECK(read_by_tiles < 2 * m.faces.size());
            }
            CHECK_THROWS_AS(tiler.tile(boxes.size(), 0.1), InvalidInput);
            CHECK_THROWS_AS(tiler.tile(0, -1), InvalidInput);
            CHECK_THROWS_AS(tiler.tile(0, std::nan("")), InvalidInput);
            CHECK_THROWS_AS(streamed.tile(boxes.size(), 0.1), InvalidInput);
            CHECK_THROWS_AS(streamed.tile(0, std::nan("")), InvalidInput);
            CHECK_THROWS_AS(
                streamed.spool(boxes.size(), 0.1, dir.path().string(), [](const SpooledTile&) {}),
                InvalidInput);
            // A tile whose use throws leaves the tiler's scratch as it found it.
            CHECK_THROWS_AS(placed.spool(0, 0.1 * side, dir.path().string(),
                                         [](const SpooledTile&) { throw std::runtime_error("x"); }),
                            std::runtime_error);
            require_same_tile(placed.tile(0, 0.1 * side), make_mesh_tile(m, boxes, 0, 0.1 * side));
            // A read of the faces that fails in the middle of a tile leaves the next tile right,
            // held or spooled: the tile in the opposite corner, which shares no vertex with the
            // faces read before the failure.
            const int last = boxes.size() - 1;
            calls = 0;
            streamed.tile(0, 0.0);
            if (count > 1 && calls >= 2) {
                ++failed_reads;
                for (bool spool : {false, true}) {
                    calls = 0;
                    fail_at_call = 2;
                    if (spool)
                        CHECK_THROWS_AS(
                            streamed.spool(0, 0.0, dir.path().string(), [](const SpooledTile&) {}),
                            std::runtime_error);
                    else
                        CHECK_THROWS_AS(streamed.tile(0, 0.0), std::runtime_error);
                    fail_at_call = 0;
                    require_same_tile(streamed.tile(last, 0.0),
                                      make_mesh_tile(m, boxes, last, 0.0));
                }
            }
        }
    }
    CHECK(failed_reads > 0);
}

TEST_CASE("depth maps made tile by tile equal the whole mesh's", "[tiles]") {
    const Mesh m = engraved_sphere(6);
    const double r = 0.04 * 2.0;  // 4% of the sphere's diameter, about its largest side
    const std::vector<DetailOrientation> both = {DetailOrientation::Positive,
                                                 DetailOrientation::Negative};
    for (DiscMode mode : {DiscMode::Exact, DiscMode::Fast}) {
        SmoothingParams p;
        p.radius = r;
        p.disc = mode;
        const std::vector<DepthMap> whole = whole_depth_maps(m, p, both);
        for (int tiles : {4, 9}) {
            INFO(name_of(mode) << ", " << tiles << " tiles");
            const std::vector<DepthMap> tiled = make_tiled_depth_maps(m, p, both, tiles);
            REQUIRE(tiled.size() == 2);
            for (int i = 0; i < 2; ++i) {
                CHECK(tiled[i].orientation == both[i]);
                CHECK(tiled[i].num_moved_vertices == whole[i].num_moved_vertices);
                CHECK(largest_difference(tiled[i], whole[i]) <= 1e-12 * r);
                CHECK(tiled[i].max_depth == Approx(whole[i].max_depth).epsilon(1e-12));
                CHECK(tiled[i].face_depth.size() == whole[i].face_depth.size());
            }
            // A halo of half a radius cuts discs short: the depths near the borders move.
            const std::vector<DepthMap> narrow = make_tiled_depth_maps(m, p, both, tiles, 0.5 * r);
            CHECK(largest_difference(narrow[0], whole[0]) > 1e-6 * r);
        }
    }
}

TEST_CASE("tiles of two components sample their discs as the whole mesh does", "[tiles]") {
    // Two bumpy spheres side by side, each cut by the tiles, with fast discs: a tile that
    // started its own sampling grid at its own corner would sample other vertices.
    const Mesh m = test::combined(test::make_sphere(1.0, 5),
                                  test::make_sphere(0.6, 5, Eigen::Vector3d(2.1, 0.3, 0)));
    const Mesh bumpy = [&] {
        Mesh b = m;
        for (auto& q : b.positions) q *= 1 + 0.03 * std::sin(9 * q.x()) * std::cos(7 * q.y());
        return b;
    }();
    SmoothingParams p;
    p.radius = 0.25;
    p.disc = DiscMode::Fast;
    const std::vector<DetailOrientation> positive = {DetailOrientation::Positive};
    const std::vector<DepthMap> whole = whole_depth_maps(bumpy, p, positive);
    for (int tiles : {2, 4, 6}) {
        INFO(tiles << " tiles");
        const std::vector<DepthMap> tiled = make_tiled_depth_maps(bumpy, p, positive, tiles);
        CHECK(largest_difference(tiled[0], whole[0]) <= 1e-12 * p.radius);
        CHECK(whole[0].max_depth > 0.01);
    }
    CHECK_THROWS_AS(make_tiled_depth_maps(bumpy, p, positive, 0), InvalidInput);
    CHECK_THROWS_AS(make_tiled_depth_maps(bumpy, p, positive, 4, -1), InvalidInput);
}

namespace {

// Texels equal in every field make_texels gives them.
void check_same_texels(const TexelSet& a, const TexelSet& b) {
    CHECK(a.global_threshold == b.global_threshold);
    CHECK(a.num_local_maxima == b.num_local_maxima);
    CHECK(a.num_regions == b.num_regions);
    CHECK(a.num_merges == b.num_merges);
    CHECK(a.face_texel == b.face_texel);
    REQUIRE(a.texels.size() == b.texels.size());
    for (std::size_t t = 0; t < a.texels.size(); ++t) {
        CHECK(a.texels[t].faces == b.texels[t].faces);
        CHECK(a.texels[t].seed == b.texels[t].seed);
        CHECK(a.texels[t].threshold == b.texels[t].threshold);
        CHECK(a.texels[t].depth_mean == b.texels[t].depth_mean);
        CHECK(a.texels[t].depth_std == b.texels[t].depth_std);
    }
}

}  // namespace

TEST_CASE("texels grown tile by tile and merged equal the whole mesh's", "[tiles]") {
    const Mesh m = engraved_sphere(6);
    SmoothingParams sp;
    sp.radius = 0.08;
    const std::vector<DetailOrientation> both = {DetailOrientation::Positive,
                                                 DetailOrientation::Negative};
    const std::vector<DepthMap> depth = whole_depth_maps(m, sp, both);
    const MeshTopology topology = make_topology(m);
    TexelParams tp;
    tp.radius = sp.radius;
    for (int tiles : {1, 4, 9}) {
        INFO(tiles << " tiles");
        const std::vector<TexelSet> tiled = make_tiled_texels(m, depth, tp, tiles);
        REQUIRE(tiled.size() == 2);
        for (int i = 0; i < 2; ++i) {
            const TexelSet whole = make_texels(m, topology, depth[i], tp);
            CHECK(whole.texels.size() >= 30);  // sphere-1's 88 shapes, about half each way
            check_same_texels(tiled[i], whole);
        }
    }
}

TEST_CASE("tiles end to end: depth maps and texels as the whole mesh's", "[tiles]") {
    const Mesh m = engraved_sphere(6);
    SmoothingParams sp;
    sp.radius = 0.08;
    sp.disc = DiscMode::Fast;
    const std::vector<DetailOrientation> positive = {DetailOrientation::Positive};
    TexelParams tp;
    tp.radius = sp.radius;
    const TexelSet whole =
        make_texels(m, make_topology(m), whole_depth_maps(m, sp, positive)[0], tp);
    const std::vector<TexelSet> tiled =
        make_tiled_texels(m, make_tiled_depth_maps(m, sp, positive, 9), tp, 9);
    CHECK(tiled[0].face_texel == whole.face_texel);
    CHECK(tiled[0].texels.size() == whole.texels.size());
}

TEST_CASE("a tile's regions are the whole mesh's of the seeds it owns, in their order", "[tiles]") {
    // Ridges 0.45r in deviation across the tiles' edges (x, y = -1/6 and 1/6), each crest one
    // seed whose region runs along it, one across the whole square, and round bumps, cut into
    // 3 x 3 tiles with the first halo of 3r: the ridges' regions reach past it, and their seeds
    // grow again around them, the longest more than once; the bumps, lower, are whole at once,
    // so that regions grown again come before some grown first. The tile's part must hold the
    // regions grown on the whole mesh from the seeds its box holds: the same faces, touch lists and
    // statistics, deepest seed first.
    const double r = 0.03;
    // A ridge along `along` from `from` to `to`, its crest at `across`, with smooth ends.
    const auto ridge = [&](double along, double across, double from, double to, double height) {
        const double w = 0.2 * r;
        return height * std::exp(-(across * across) / (2 * 0.2 * r * r)) /
               ((1 + std::exp(-(along - from) / w)) * (1 + std::exp((along - to) / w)));
    };
    const Mesh m = test::make_grid(150, 1.0, [&](double x, double y) {
        double z = ridge(x, y - 0.03, -1, 1, 0.5 * r) + ridge(x, y + 0.3, 0.0, 0.35, 0.55 * r) +
                   ridge(y, x + 0.3, -0.1, 0.3, 0.6 * r) +
                   ridge(x, y - 0.33, -0.35, 0.0, 0.65 * r) +
                   ridge(y, x - 0.32, -0.35, 0.0, 0.7 * r);
        for (const auto& b : {Eigen::Vector2d(0.0, -0.1), Eigen::Vector2d(0.3, 0.3)})
            z += 0.45 * r *
                 std::exp(-((x - b.x()) * (x - b.x()) + (y - b.y()) * (y - b.y())) / (2 * r * r));
        return z;
    });
    DepthMap d;
    d.vertex_depth.resize(m.positions.size());
    for (std::size_t v = 0; v < m.positions.size(); ++v) d.vertex_depth[v] = m.positions[v].z();
    set_face_depths(m, d);
    TexelParams tp;
    tp.radius = r;
    const MeshTopology topology = make_topology(m);
    const double threshold = texel_global_threshold(d.vertex_depth, tp);
    const TileBoxes boxes = make_tile_boxes(m.positions, 9);
    int grown_again = 0, seeds = 0;
    for (int b = 0; b < boxes.size(); ++b) {
        INFO("tile " << b);
        const std::optional<TilePart> part =
            detail::texel_part(m, {&d}, {threshold}, tp, boxes, b, kTexelHaloRadii * r);
        REQUIRE(part);
        std::vector<char> owned(m.positions.size(), 0);
        for (std::size_t v = 0; v < m.positions.size(); ++v)
            owned[v] = boxes.box_of(m.positions[v]) == b ? 1 : 0;
        const TexelRegions whole = grow_texel_regions(m, topology, d, tp, threshold, owned);
        const TexelRegions& tiled = part->regions[0];
        CHECK(tiled.num_seeds == whole.num_seeds);
        REQUIRE(tiled.regions.size() == whole.regions.size());
        const RegionDepths& depths = part->region_depths[0];
        REQUIRE(depths.seed.size() == whole.regions.size());
        std::size_t face = 0;
        for (std::size_t k = 0; k < whole.regions.size(); ++k) {
            const TexelRegion &x = tiled.regions[k], &y = whole.regions[k];
            CHECK(x.seed == y.seed);
            CHECK(x.faces == y.faces);
            CHECK(x.touch == y.touch);
            CHECK(x.threshold == y.threshold);
            CHECK(x.mean == y.mean);
            CHECK(x.std == y.std);
            CHECK(depths.seed[k] == d.vertex_depth[static_cast<std::size_t>(y.seed)]);
            for (int f : y.faces) CHECK(depths.face[face++] == d.face_depth[f]);
            // Reached past the first halo (a face more than 3r from the box).
            bool past = false;
            for (int f : y.faces)
                for (int v : m.faces[f])
                    past = past || boxes.distance(b, m.positions[v]) > kTexelHaloRadii * r;
            grown_again += past;
        }
        CHECK(face == depths.face.size());
        seeds += whole.num_seeds;
    }
    CHECK(seeds >= 7);
    CHECK(grown_again >= 5);
}

TEST_CASE("a tile widens its halo for a texel longer than the halo", "[tiles]") {
    // A ridge along the whole grid: one region from end to end, cut by 2 x 2 and 3 x 3 tiles
    // whose halo of r holds a small part of it.
    const Mesh m =
        test::make_grid(80, 4.0, [](double, double y) { return 0.1 * std::exp(-y * y / 0.02); });
    DepthMap d;
    d.vertex_depth.resize(m.positions.size());
    for (std::size_t v = 0; v < m.positions.size(); ++v) d.vertex_depth[v] = m.positions[v].z();
    set_face_depths(m, d);
    TexelParams tp;
    tp.radius = 0.15;
    const TexelSet whole = make_texels(m, make_topology(m), d, tp);
    REQUIRE(whole.texels.size() == 1);
    double from = 0, to = 0;  // the ridge's extent along x: nearly the grid's 4
    for (int f : whole.texels[0].faces)
        for (int v : m.faces[f]) {
            from = std::min(from, m.positions[v].x());
            to = std::max(to, m.positions[v].x());
        }
    CHECK(to - from > 3.5);
    for (int tiles : {1, 4, 9}) {
        INFO(tiles << " tiles");
        check_same_texels(make_tiled_texels(m, {d}, tp, tiles, tp.radius)[0], whole);
    }
}

namespace {

// The same texels and textures as the whole run, and features equal to rounding.
void check_same_segmentation(const Segmentation& tiled, const Segmentation& whole) {
    CHECK(tiled.radius == whole.radius);
    CHECK(tiled.metrics.vertex_normal == whole.metrics.vertex_normal);
    CHECK(tiled.metrics.vertex_area == whole.metrics.vertex_area);
    CHECK(tiled.metrics.face_area == whole.metrics.face_area);
    CHECK(tiled.metrics.mean_edge_length == whole.metrics.mean_edge_length);
    CHECK(tiled.num_interpolated_vertices == whole.num_interpolated_vertices);
    CHECK(tiled.num_disc_samples == whole.num_disc_samples);
    CHECK(tiled.runs == whole.runs);
    CHECK(tiled.run_excluded_texels == whole.run_excluded_texels);
    CHECK(tiled.face_texel == whole.face_texel);
    REQUIRE(tiled.texels.size() == whole.texels.size());
    for (std::size_t t = 0; t < whole.texels.size(); ++t) {
        CHECK(tiled.texels[t].faces == whole.texels[t].faces);
        CHECK(tiled.texels[t].orientation == whole.texels[t].orientation);
        CHECK(tiled.texels[t].seed == whole.texels[t].seed);
    }
    CHECK(tiled.num_textures == whole.num_textures);
    CHECK(tiled.texel_texture == whole.texel_texture);
    CHECK(tiled.face_texture == whole.face_texture);
    REQUIRE(tiled.features.values.rows() == whole.features.values.rows());
    CHECK((tiled.features.values - whole.features.values).cwiseAbs().maxCoeff() <= 1e-9);
    std::size_t same_curvature = 0, texel_vertices = 0;
    for (std::size_t v = 0; v < whole.curvature.gaussian.size(); ++v) {
        const double a = whole.curvature.curvedness[v], b = tiled.curvature.curvedness[v];
        if (std::isnan(a) && std::isnan(b)) continue;
        ++texel_vertices;
        same_curvature += std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a)) ? 1 : 0;
    }
    CHECK(same_curvature == texel_vertices);
    CHECK(tiled.diagnostics.size() == whole.diagnostics.size());
}

}  // namespace

TEST_CASE("a segmentation made in tiles equals the whole run", "[tiles]") {
    const Mesh m = engraved_sphere(6);
    struct Case {
        OrientationMode orientation;
        bool remove_rims;
    };
    for (const Case c : {Case{OrientationMode::Both, true}, Case{OrientationMode::Positive, true},
                         Case{OrientationMode::Negative, false}}) {
        SegmentationParams p;
        p.radius_rel = 0.04;
        p.orientation = c.orientation;
        p.remove_rims = c.remove_rims;
        const Segmentation whole = run_segmentation(m, p);
        CHECK(whole.texels.size() >= 30);
        CHECK(whole.num_textures >= 2);
        if (c.remove_rims)  // the rim removal's second smoothing is exercised
            CHECK(std::accumulate(whole.run_excluded_texels.begin(),
                                  whole.run_excluded_texels.end(), 0) > 0);
        for (int tiles : {4, 9}) {
            INFO(name_of(c.orientation)
                 << (c.remove_rims ? "" : ", rims kept") << ", " << tiles << " tiles");
            check_same_segmentation(run_tiled_segmentation(m, p, tiles), whole);
        }
    }
    SegmentationParams p;
    CHECK_THROWS_AS(run_tiled_segmentation(m, p, 0), InvalidInput);
    CHECK_THROWS_AS(run_tiled_segmentation(Mesh{}, p, 4), InvalidInput);
    p.radius_rel = 2;
    CHECK_THROWS_AS(run_tiled_segmentation(m, p, 4), InvalidInput);
    // A mesh far from unit size: the whole run's unit frame is not done in tiles.
    CHECK_THROWS_WITH(run_tiled_segmentation(test::scaled(m, 1e12), SegmentationParams{}, 4),
                      Catch::Contains("scale it first"));
}
