// Tiles run as separate jobs (geometry/tiles.hpp TiledSegmentation, pipeline/tile_parts.hpp):
// each pass's parts written to bytes, read back and joined in any order give the segmentation
// of the one-process tiled run bit for bit, and a part of another run, pass or tile, a damaged
// part or a missing tile is refused with what is wrong. A texel pass's texels joined once and
// written (pipeline/joined_texels.hpp) read back bit for bit and give the join the same
// result as the parts.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/tile_alone.hpp"
#include "geometry/tiled_segmentation.hpp"
#include "pipeline/joined_texels.hpp"
#include "pipeline/report_json.hpp"
#include "pipeline/tile_parts.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

std::string bytes_of(const std::string& key, const TilePart& part) {
    std::ostringstream out;
    write_tile_part(out, key, part);
    return out.str();
}

// Equal values, NaN equal to NaN (0.0 equals -0.0, unlike test::same_bits).
bool same_value(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

bool same_field(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!same_value(a[i], b[i])) return false;
    return true;
}

// Every pass of `maker` to the end, each tile's part joined by `maker` and by each of `joins`,
// which must wait for the same pass.
void join_every_pass(TiledSegmentation& maker, const std::vector<TiledSegmentation*>& joins) {
    while (maker.pass() != TilePass::Done) {
        for (TiledSegmentation* j : joins) REQUIRE(j->pass() == maker.pass());
        for (int b = 0; b < maker.num_tiles(); ++b) {
            TilePart part = maker.run_tile(b);
            for (TiledSegmentation* j : joins) j->add(part);
            maker.add(std::move(part));
        }
        maker.finish_pass();
        for (TiledSegmentation* j : joins) j->finish_pass();
    }
    for (TiledSegmentation* j : joins) REQUIRE(j->pass() == TilePass::Done);
}

// Both orientations at scale `rel`: the half-engraved sphere then needs every pass.
SegmentationParams both_at(double rel) {
    SegmentationParams p;
    p.radius_rel = rel;
    p.orientation = OrientationMode::Both;
    return p;
}

// The texels of texel pass `pass` joined from its parts, as the first job after it joins them.
JoinedTexels join_parts(const TiledSegmentation& maker, TilePass pass, const DepthTile& first,
                        const SegmentationParams& p, const std::vector<TilePart>& parts) {
    const DepthPassOf of{pass == TilePass::Texels ? TilePass::Depth : TilePass::DepthWithoutRims,
                         maker.orientations()};
    return join_texels(first, p, of, [&](int k) { return parts[static_cast<std::size_t>(k)]; });
}

std::string joined_bytes(const std::string& key, TilePass pass, const JoinedTexels& joined) {
    std::ostringstream out;
    write_joined_texels(out, key, pass, joined);
    return out.str();
}

JoinedTexels read_joined(const std::string& bytes, const std::string& key, TilePass pass) {
    std::istringstream in(bytes);
    return read_joined_texels(in, key, pass);
}

}  // namespace

TEST_CASE("tile parts written, read back and joined in any order give the tiled run's result",
          "[tiles]") {
    const Mesh m = test::half_engraved_sphere(6);
    const SegmentationParams p = both_at(0.04);
    const int tiles = 4;
    const Segmentation reference = run_tiled_segmentation(m, p, tiles);
    const std::string key = tile_run_key("mesh digest", p, tiles);

    TiledSegmentation run(m, p, tiles);
    std::vector<TilePass> passes;
    while (run.pass() != TilePass::Done) {
        passes.push_back(run.pass());
        // Made in one order, joined in the reverse: a job per tile finishes when it does.
        std::vector<std::string> files;
        for (int b = 0; b < run.num_tiles(); ++b) files.push_back(bytes_of(key, run.run_tile(b)));
        for (int b = run.num_tiles() - 1; b >= 0; --b) {
            if (b == 1) {
                CHECK(run.missing() == std::vector<int>{0, 1});
                CHECK_THROWS_WITH(run.finish_pass(), Catch::Contains("tiles 1, 2"));
            }
            run.add(read_tile_part(files[b], key, run.pass(), b));
        }
        CHECK(run.missing().empty());
        // A tile's part twice is refused.
        CHECK_THROWS_WITH(run.add(read_tile_part(files[0], key, run.pass(), 0)),
                          Catch::Contains("in already"));
        run.finish_pass();
    }
    // The engraved sphere needs every pass: both orientations, and details left out of the
    // second smoothing.
    CHECK(passes == std::vector<TilePass>{TilePass::Depth, TilePass::Texels, TilePass::Rims,
                                          TilePass::DepthWithoutRims, TilePass::TexelsWithoutRims,
                                          TilePass::Features});
    const Segmentation joined = std::move(run).result();
    CHECK(joined.face_texel == reference.face_texel);
    CHECK(joined.face_texture == reference.face_texture);
    CHECK(joined.texel_texture == reference.texel_texture);
    CHECK(joined.run_excluded_texels == reference.run_excluded_texels);
    CHECK(joined.num_interpolated_vertices == reference.num_interpolated_vertices);
    CHECK(joined.features.values == reference.features.values);
    CHECK(same_field(joined.curvature.curvedness, reference.curvature.curvedness));
    CHECK(same_field(joined.positive_depth->vertex_depth, reference.positive_depth->vertex_depth));
    CHECK(same_field(joined.negative_depth->face_depth, reference.negative_depth->face_depth));
    CHECK(joined.texels.size() >= 30);
}

TEST_CASE("a tiled run kept for its outputs reports the same without the arrays no output reads",
          "[tiles]") {
    const Mesh m = test::half_engraved_sphere(5);
    const SegmentationParams p = both_at(0.05);
    const int tiles = 4;
    // The parts are made by a run that keeps everything and joined by both.
    TiledSegmentation maker(m, p, tiles);
    TiledSegmentation kept(m, p, tiles, TiledResult::Outputs);
    CHECK_THROWS_WITH(kept.run_tile(0), Catch::Contains("makes none"));
    join_every_pass(maker, {&kept});
    const Segmentation whole = std::move(maker).result();
    const Segmentation outputs = std::move(kept).result();
    REQUIRE(whole.texels.size() >= 10);
    REQUIRE(!whole.metrics.vertex_area.empty());
    REQUIRE(!whole.curvature.mean.empty());
    CHECK(outputs.metrics.vertex_area.empty());
    CHECK(outputs.metrics.vertex_normal.empty());
    CHECK(outputs.metrics.face_area.empty());
    CHECK(outputs.curvature.mean.empty());
    CHECK(outputs.positive_depth->vertex_depth.empty());
    CHECK(outputs.negative_depth->face_depth.empty());
    CHECK(outputs.negative_depth->max_depth == whole.negative_depth->max_depth);
    CHECK(outputs.positive_depth->num_moved_vertices == whole.positive_depth->num_moved_vertices);
    CHECK(outputs.run_excluded_texels == whole.run_excluded_texels);
    CHECK(outputs.metrics.largest_side == whole.metrics.largest_side);
    // No face labels: the PLY writer makes them from the texels, a block of faces at a time.
    CHECK(outputs.face_texel.empty());
    CHECK(outputs.face_texture.empty());
    CHECK(outputs.metrics.num_faces == m.num_faces());
    FaceLabelCursor labels(outputs);
    std::vector<int> face_texel, face_texture, texel, texture;
    for (int first = 0; first < m.num_faces(); first += 100) {
        labels.next(first, std::min(100, m.num_faces() - first), texel, texture);
        face_texel.insert(face_texel.end(), texel.begin(), texel.end());
        face_texture.insert(face_texture.end(), texture.begin(), texture.end());
    }
    CHECK(face_texel == whole.face_texel);
    CHECK(face_texture == whole.face_texture);
    CHECK(outputs.features.values == whole.features.values);
    // The report counts the mesh's vertices without the metrics' arrays.
    const ReportInput input{"sphere.ply", "ply-binary", {}};
    const std::string report = segmentation_report(outputs, p, input).dump();
    CHECK(report == segmentation_report(whole, p, input).dump());
    CHECK(report.find("\"vertices\":" + std::to_string(m.num_vertices())) != std::string::npos);
}

TEST_CASE("a join over the positions alone, looking up a face a texel, reports the same",
          "[tiles]") {
    const Mesh m = test::half_engraved_sphere(5);
    const SegmentationParams p = both_at(0.05);
    const int tiles = 4;
    // The join's mesh: the positions, the extent, and the faces it asks for, counted.
    Mesh vertices;
    vertices.positions = m.positions;
    MeshOutline outline{vertices.positions, make_mesh_extent(m), {}, {}, {}};
    std::size_t looked_up = 0;
    outline.faces = [&](const std::vector<int>& ids) {
        CHECK(std::is_sorted(ids.begin(), ids.end()));
        looked_up += ids.size();
        std::vector<std::array<int, 3>> faces;
        for (int f : ids) faces.push_back(m.faces[f]);
        return faces;
    };
    TiledSegmentation maker(m, p, tiles);
    TiledSegmentation kept(m, p, tiles, TiledResult::Outputs);
    TiledSegmentation outlined(outline, p, tiles);
    CHECK_THROWS_WITH(outlined.run_tile(0), Catch::Contains("makes none"));
    join_every_pass(maker, {&kept, &outlined});
    const Segmentation a = std::move(kept).result();
    const Segmentation b = std::move(outlined).result();
    REQUIRE(a.texels.size() >= 10);
    CHECK(looked_up <= a.texels.size());
    CHECK(looked_up > 0);
    CHECK(b.texel_texture == a.texel_texture);
    CHECK(b.features.values == a.features.values);
    for (std::size_t t = 0; t < a.texels.size(); ++t) CHECK(b.texels[t].faces == a.texels[t].faces);
    const ReportInput input{"sphere.ply", "ply-binary", {}};
    CHECK(segmentation_report(b, p, input).dump() == segmentation_report(a, p, input).dump());
    // An outline without its faces is a caller's mistake; one of no face, a mesh's.
    CHECK_THROWS_AS(
        TiledSegmentation(MeshOutline{vertices.positions, outline.extent, {}, {}, {}}, p, tiles),
        std::invalid_argument);
    MeshOutline empty = outline;
    empty.extent.num_faces = 0;
    CHECK_THROWS_WITH(TiledSegmentation(empty, p, tiles), Catch::Contains("no face"));
}

TEST_CASE("FaceLabelCursor refuses a face in two texels", "[tiles]") {
    Segmentation seg;
    seg.texels.resize(2);
    seg.texels[0].faces = {1, 4};
    seg.texels[1].faces = {2, 4};
    seg.texel_texture = {0, 0};
    CHECK_THROWS_WITH(FaceLabelCursor(seg), Catch::Contains("face 4 is in two texels"));
}

TEST_CASE("a tile part of another run, pass or tile, or damaged, is refused", "[tiles]") {
    const Mesh m = test::half_engraved_sphere(5);
    const SegmentationParams p = both_at(0.05);
    const std::string key = tile_run_key("digest", p, 4);
    // The key changes with the mesh, any option and the number of tiles.
    CHECK(tile_run_key("other digest", p, 4) != key);
    CHECK(tile_run_key("digest", p, 9) != key);
    SegmentationParams q = p;
    q.min_faces += 1;
    CHECK(tile_run_key("digest", q, 4) != key);

    TiledSegmentation run(m, p, 4);
    const TilePart part = run.run_tile(2);
    const std::string bytes = bytes_of(key, part);
    CHECK_NOTHROW(read_tile_part(bytes, key, TilePass::Depth, 2));
    CHECK_THROWS_WITH(read_tile_part(bytes, tile_run_key("other digest", p, 4), TilePass::Depth, 2),
                      Catch::Contains("another run"));
    CHECK_THROWS_WITH(read_tile_part(bytes, key, TilePass::Texels, 2),
                      Catch::Contains("pass depth, not texels"));
    CHECK_THROWS_WITH(read_tile_part(bytes, key, TilePass::Depth, 1),
                      Catch::Contains("tile 3, not 2"));
    CHECK_THROWS_WITH(read_tile_part(bytes.substr(0, bytes.size() / 2), key, TilePass::Depth, 2),
                      Catch::Contains("not a geotex tile part"));
    CHECK_THROWS_WITH(read_tile_part("{}", key, TilePass::Depth, 2),
                      Catch::Contains("not a geotex tile part"));

    // Parts that read well but do not fit the run are refused when they join it.
    TilePart wrong = part;
    wrong.vertices.back() = m.num_vertices();  // past the last vertex
    CHECK_THROWS_WITH(run.add(wrong), Catch::Contains("vertex ids"));
    wrong = part;
    wrong.tile = 0;  // its vertices are in tile 3's box
    CHECK_THROWS_WITH(run.add(wrong), Catch::Contains("not in its box"));
    wrong = part;
    wrong.depths.pop_back();
    CHECK_THROWS_WITH(run.add(wrong), Catch::Contains("orientations"));
    wrong = part;
    wrong.pass = TilePass::Texels;
    CHECK_THROWS_WITH(run.add(wrong), Catch::Contains("waits for pass depth"));
    CHECK_THROWS_AS(run.run_tile(4), InvalidInput);
    CHECK_THROWS_WITH(TiledSegmentation(m, p, 4).result(), Catch::Contains("waits for pass depth"));
}

TEST_CASE(
    "joined texels written and read back are the same, bit for bit; another run's or "
    "pass's, or a damaged file, is refused",
    "[tiles]") {
    const Mesh m = test::half_engraved_sphere(5);
    const SegmentationParams p = both_at(0.05);
    TiledSegmentation maker(m, p, 4);
    const DepthTile first = maker.depth_tile(0);
    while (maker.pass() != TilePass::Texels) {
        for (int b = 0; b < maker.num_tiles(); ++b) maker.add(maker.run_tile(b));
        maker.finish_pass();
    }
    std::vector<TilePart> parts;
    for (int b = 0; b < maker.num_tiles(); ++b) parts.push_back(maker.run_tile(b));
    const JoinedTexels joined = join_parts(maker, TilePass::Texels, first, p, parts);
    const std::string bytes = joined_bytes("k", TilePass::Texels, joined);
    const JoinedTexels read = read_joined(bytes, "k", TilePass::Texels);
    for (std::size_t o = 0; o < 2; ++o) {
        const TexelSet &a = read.texels[o], &b = joined.texels[o];
        REQUIRE(b.texels.size() >= 3);
        REQUIRE(a.texels.size() == b.texels.size());
        for (std::size_t t = 0; t < b.texels.size(); ++t) {
            CHECK(a.texels[t].faces == b.texels[t].faces);
            CHECK(a.texels[t].seed == b.texels[t].seed);
            CHECK(a.texels[t].orientation == b.texels[t].orientation);
            CHECK(test::same_bits(a.texels[t].threshold, b.texels[t].threshold));
            CHECK(test::same_bits(a.texels[t].depth_mean, b.texels[t].depth_mean));
            CHECK(test::same_bits(a.texels[t].depth_std, b.texels[t].depth_std));
            CHECK(test::same_bits(read.depth[o][t], joined.depth[o][t]));
        }
        CHECK(test::same_bits(a.global_threshold, b.global_threshold));
        CHECK(a.num_local_maxima == b.num_local_maxima);
        CHECK(a.num_regions == b.num_regions);
        CHECK(a.num_merges == b.num_merges);
        REQUIRE(a.diagnostics.size() == b.diagnostics.size());
        for (std::size_t d = 0; d < b.diagnostics.size(); ++d) {
            CHECK(a.diagnostics[d].stage == b.diagnostics[d].stage);
            CHECK(a.diagnostics[d].message == b.diagnostics[d].message);
        }
        CHECK(a.face_texel.empty());
    }
    // Written again, the same bytes.
    CHECK(joined_bytes("k", TilePass::Texels, read) == bytes);

    const auto refusal = [](const std::string& content, const std::string& key, TilePass pass) {
        try {
            read_joined(content, key, pass);
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK_THAT(refusal(bytes, "k2", TilePass::Texels),
               Catch::Contains("the joined texels file of another run"));
    CHECK_THAT(
        refusal(bytes, "k", TilePass::TexelsWithoutRims),
        Catch::Contains("the joined texels of pass texels, not of pass texels-without-rims"));
    CHECK_THAT(refusal("geotex tile part\n" + bytes.substr(21), "k", TilePass::Texels),
               Catch::Contains("not a geotex joined texels file"));
    CHECK_THAT(refusal(bytes.substr(0, bytes.size() - 1), "k", TilePass::Texels),
               Catch::Contains("damaged: the file ends inside its arrays"));
    CHECK_THAT(refusal(bytes + "x", "k", TilePass::Texels),
               Catch::Contains("damaged: bytes past the end of its arrays"));
    CHECK_THAT(refusal(bytes.substr(0, 40), "k", TilePass::Texels),
               Catch::Contains("damaged: the file ends in its header"));
    JoinedTexels unsorted = joined;
    std::swap(unsorted.texels[1].texels[2].faces[0], unsorted.texels[1].texels[2].faces[1]);
    CHECK_THAT(refusal(joined_bytes("k", TilePass::Texels, unsorted), "k", TilePass::Texels),
               Catch::Contains("damaged: the faces of texel 2 do not ascend"));
    JoinedTexels no_depth = joined;
    no_depth.depth[0].pop_back();
    CHECK_THROWS_WITH(joined_bytes("k", TilePass::Texels, no_depth),
                      Catch::Contains("depths are not one a texel"));
    CHECK_THROWS_WITH(joined_bytes("k", TilePass::Rims, joined),
                      Catch::Contains("not of a texel pass"));
}

TEST_CASE(
    "a run kept for its outputs takes each depth part's summary and each texel pass's "
    "texels joined once, and reports the same as from the parts",
    "[tiles]") {
    const Mesh m = test::half_engraved_sphere(5);
    SegmentationParams p = both_at(0.05);
    p.disc = DiscMode::Fast;  // so that the first depth pass counts its samples
    const int tiles = 4;
    TiledSegmentation maker(m, p, tiles);
    TiledSegmentation kept(m, p, tiles, TiledResult::Outputs);
    TiledSegmentation taken(m, p, tiles, TiledResult::Outputs);
    const DepthTile first = maker.depth_tile(0);
    CHECK_THROWS_WITH(taken.finish_texel_pass({}), Catch::Contains("waits for pass depth"));
    int texel_passes = 0, depth_passes = 0;
    while (maker.pass() != TilePass::Done) {
        const TilePass pass = maker.pass();
        REQUIRE(kept.pass() == pass);
        REQUIRE(taken.pass() == pass);
        std::vector<TilePart> parts;
        for (int b = 0; b < tiles; ++b) parts.push_back(maker.run_tile(b));
        for (const TilePart& part : parts) kept.add(part);
        if (pass == TilePass::Texels || pass == TilePass::TexelsWithoutRims) {
            ++texel_passes;
            // Through the file a job leaves, as the join of the outputs reads it.
            JoinedTexels joined = read_joined(
                joined_bytes("k", pass, join_parts(maker, pass, first, p, parts)), "k", pass);
            CHECK_THROWS_WITH(maker.finish_texel_pass(joined.texels),
                              Catch::Contains("only a run kept for its outputs"));
            std::array<TexelSet, 2> past = joined.texels;
            past[1].texels.back().faces.back() = m.num_faces();
            CHECK_THROWS_WITH(taken.finish_texel_pass(past),
                              Catch::Contains("its faces are not the mesh's"));
            std::array<TexelSet, 2> swapped = joined.texels;
            std::swap(swapped[0], swapped[1]);
            CHECK_THROWS_WITH(taken.finish_texel_pass(swapped),
                              Catch::Contains("not of its orientation"));
            taken.finish_texel_pass(std::move(joined.texels));
        } else if (is_depth_pass(pass)) {
            // By each part's summary, as the join reads it from the sorted depths.
            ++depth_passes;
            for (const TilePart& part : parts) {
                DepthPartSummary summary{
                    part.tile, {}, part.moved, part.interpolated, part.samples};
                for (const std::vector<double>& depths : part.depths) {
                    double most = 0;
                    for (double d : depths) most = std::max(most, d);
                    summary.greatest.push_back(most);
                }
                if (part.tile == 0) {
                    CHECK_THROWS_WITH(maker.add_depth_summary(summary),
                                      Catch::Contains("only a run kept for its outputs"));
                    DepthPartSummary one = summary;
                    one.moved.pop_back();
                    CHECK_THROWS_WITH(taken.add_depth_summary(one), Catch::Contains("not 2"));
                }
                taken.add_depth_summary(summary);
            }
            CHECK_THROWS_WITH(taken.add(parts[0]), Catch::Contains("in already"));
            taken.finish_pass();
        } else {
            if (pass == TilePass::Rims) {
                DepthPartSummary rims{0, {0.0, 0.0}, {0, 0}, 0, 0};
                CHECK_THROWS_WITH(taken.add_depth_summary(rims),
                                  Catch::Contains("the run waits for pass rims"));
            }
            for (const TilePart& part : parts) taken.add(part);
            taken.finish_pass();
        }
        for (TilePart& part : parts) maker.add(std::move(part));
        maker.finish_pass();
        kept.finish_pass();
    }
    // Both orientations and a second smoothing: two depth and two texel passes.
    CHECK(texel_passes == 2);
    CHECK(depth_passes == 2);
    const Segmentation a = std::move(kept).result();
    const Segmentation b = std::move(taken).result();
    REQUIRE(a.texels.size() >= 10);
    REQUIRE(b.texels.size() == a.texels.size());
    for (std::size_t t = 0; t < a.texels.size(); ++t) CHECK(b.texels[t].faces == a.texels[t].faces);
    CHECK(b.texel_texture == a.texel_texture);
    CHECK(b.features.values == a.features.values);
    CHECK(b.run_excluded_texels == a.run_excluded_texels);
    // The depth maps' numbers, against the run that holds them whole.
    const Segmentation w = std::move(maker).result();
    REQUIRE(w.num_disc_samples > 0);
    CHECK(b.num_interpolated_vertices == w.num_interpolated_vertices);
    CHECK(b.num_disc_samples == w.num_disc_samples);
    REQUIRE(w.positive_depth->num_moved_vertices > 0);
    REQUIRE(w.negative_depth->num_moved_vertices > 0);
    CHECK(test::same_bits(b.positive_depth->max_depth, w.positive_depth->max_depth));
    CHECK(test::same_bits(b.negative_depth->max_depth, w.negative_depth->max_depth));
    CHECK(b.positive_depth->num_moved_vertices == w.positive_depth->num_moved_vertices);
    CHECK(b.negative_depth->num_moved_vertices == w.negative_depth->num_moved_vertices);
    const ReportInput input{"sphere.ply", "ply-binary", {}};
    CHECK(segmentation_report(b, p, input).dump() == segmentation_report(a, p, input).dump());
}
