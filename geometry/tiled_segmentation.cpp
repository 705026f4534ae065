#include "geometry/tiled_segmentation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/depth_tile_cutter.hpp"
#include "geometry/detail/segmentation_steps.hpp"
#include "geometry/detail/tile_steps.hpp"
#include "geometry/topology.hpp"
#include "geometry/unit_frame.hpp"

namespace geotex {

using detail::ascending_ids;
using detail::expect_depth_part;
using detail::expect_part;
using detail::first_depth_orientations;
using detail::index_of;

namespace {

// A depth map of the whole mesh on a tile's vertices and faces; the deepest vertex stays the
// whole mesh's (the features scale depths by it).
DepthMap depth_in_tile(const DepthMap& whole, const MeshTile& tile) {
    DepthMap d;
    d.orientation = whole.orientation;
    d.vertex_depth = detail::restricted(whole.vertex_depth, tile.vertex);
    d.face_depth = detail::restricted(whole.face_depth, tile.face);
    d.max_depth = whole.max_depth;
    d.num_moved_vertices = whole.num_moved_vertices;
    return d;
}

// The stage a pass is reported as.
const char* stage_of(TilePass pass) {
    switch (pass) {
        case TilePass::Depth:
            return "depth maps (tiles)";
        case TilePass::Texels:
            return "texels (tiles)";
        case TilePass::Rims:
            return "rims (tiles)";
        case TilePass::DepthWithoutRims:
            return "depth maps (tiles, without rims)";
        case TilePass::TexelsWithoutRims:
            return "texels (tiles, without rims)";
        case TilePass::Features:
            return "curvature, features and clustering (tiles)";
        case TilePass::Done:
            break;
    }
    return "done";
}

}  // namespace

// The state of a tiled run between passes: what the passes so far have joined.
struct TiledSegmentation::State {
    const Mesh* whole_mesh;  // null with a MeshOutline, which has no faces to hold
    PositionSpan positions;  // the mesh's
    int num_faces = 0;
    // The faces of the ids given, from the mesh or, with a MeshOutline, from its lookup.
    std::function<std::vector<std::array<int, 3>>(const std::vector<int>&)> faces_of;
    SegmentationParams params;
    TiledResult result;
    TileBoxes boxes;
    Segmentation seg;
    SmoothingParams sp;
    TexelParams tp;
    RimParams rp;
    double depth_halo = 0;
    // The depth passes' tiles, and the mesh job's.
    detail::DepthTileCutter cutter;

    TilePass pass = TilePass::Depth;
    std::vector<DetailOrientation> orientations;  // of the current depth or texel pass
    std::vector<char> added;                      // #tiles: its part of this pass is in
    std::array<DepthMap, 2> depth;                // positive, negative
    std::array<TexelSet, 2> texels;
    // Texel passes: each orientation's seeds' threshold and the regions so far; with
    // TiledResult::Outputs, which keeps no depth map, joined with the depths their parts carry.
    std::vector<double> thresholds;
    std::vector<TexelRegions> regions;
    std::vector<detail::TexelRegionJoin> joins;
    // Rims: the texels' depths over the whole mesh, the flags so far, and for each run the
    // texels of the other orientation that its second smoothing leaves out.
    std::array<std::vector<double>, 2> texel_depth;
    RimFlags flags;
    std::array<std::vector<char>, 2> use;
    // Features: each run's texel range, each tile's texels and how far they reach from its box.
    std::vector<std::pair<int, int>> ranges;
    std::vector<std::vector<int>> assigned;
    std::vector<double> reach;
    FeatureRows rows;

    State(const Mesh& m, const SegmentationParams& p, TiledResult r)
        : whole_mesh(&m),
          positions(m.positions),
          num_faces(m.num_faces()),
          params(p),
          result(r),
          cutter(m) {
        faces_of = [&m](const std::vector<int>& ids) {
            std::vector<std::array<int, 3>> out;
            out.reserve(ids.size());
            for (int f : ids) out.push_back(m.faces[f]);
            return out;
        };
    }
    State(const MeshOutline& outline, const SegmentationParams& p)
        : whole_mesh(nullptr),
          positions(outline.positions),
          num_faces(outline.extent.num_faces),
          faces_of(outline.faces),
          params(p),
          result(TiledResult::Outputs),
          cutter(outline) {}

    // The whole mesh, which a run made from a MeshOutline has not: only the steps of a run
    // made from a Mesh ask for it.
    const Mesh& mesh() const { return *whole_mesh; }
    int num_vertices() const { return static_cast<int>(positions.size()); }

    void begin(const MeshMetrics& extent, int tiles);

    void begin_depth(TilePass next, std::vector<DetailOrientation> which);
    void begin_texels(TilePass next);
    void begin_rims();
    void begin_features();
    void start(TilePass next);  // clears `added`

    TilePart depth_tile(int b) const;
    TilePart texel_tile(int b) const;
    TilePart rim_tile(int b) const;
    TilePart feature_tile(int b) const;

    // Refuses `what` (what the join takes in place of a pass's parts) unless the run is kept
    // for its outputs and waits for a pass of the kind it replaces (`right_pass`).
    void expect_outputs_at(bool right_pass, const std::string& what) const;
    // Refuses a part of pass `of` and tile `tile` that the run does not wait for.
    void expect_awaited(TilePass of, int tile) const;
    void add_depth(const TilePart& part);
    void add_depth_summary(const DepthPartSummary& part);  // the greatest and moved alone
    void add_texels(TilePart& part);
    void add_rims(const TilePart& part);
    void add_features(TilePart& part);
    void finish_rims();
    void finish_texels();  // once `texels` are merged
};

void TiledSegmentation::State::finish_texels() {
    regions.clear();
    joins.clear();
    // With one orientation empty no texel can be the other's rim (make_rims).
    if (pass == TilePass::Texels && params.remove_rims && !texels[0].texels.empty() &&
        !texels[1].texels.empty())
        begin_rims();
    else
        begin_features();
}

void TiledSegmentation::State::start(TilePass next) {
    pass = next;
    added.assign(static_cast<std::size_t>(boxes.size()), 0);
}

void TiledSegmentation::State::begin_depth(TilePass next, std::vector<DetailOrientation> which) {
    orientations = std::move(which);
    // The maps' arrays are made by the first part joined (add_depth), so that a job that only
    // makes parts of this pass never holds them: 8 bytes a vertex for each orientation.
    for (DetailOrientation o : orientations) {
        depth[index_of(o)] = DepthMap{};
        depth[index_of(o)].orientation = o;
    }
    start(next);
}

void TiledSegmentation::State::begin_texels(TilePass next) {
    // Without the depth maps, the first part joined gives the thresholds, which every other
    // part must carry too (add_texels).
    thresholds.clear();
    if (result == TiledResult::Whole)
        for (DetailOrientation o : orientations)
            thresholds.push_back(texel_global_threshold(depth[index_of(o)].vertex_depth, tp));
    regions.assign(orientations.size(), {});
    joins.assign(orientations.size(), {});
    start(next);
}

void TiledSegmentation::State::begin_rims() {
    // Without the depth maps, the merge of the texels gave these (TexelRegionJoin::merge).
    if (result == TiledResult::Whole) {
        texel_depth[0] = texel_depths(mesh(), texels[0], depth[0]);
        texel_depth[1] = texel_depths(mesh(), texels[1], depth[1]);
    }
    flags = no_rim_flags(texels[0].texels.size(), texels[1].texels.size());
    start(TilePass::Rims);
}

void TiledSegmentation::State::begin_features() {
    std::vector<detail::OrientationResult> results;
    for (DetailOrientation o : seg.runs)
        results.push_back({o, std::move(depth[index_of(o)]), std::move(texels[index_of(o)])});
    // The outputs' labels are made as the faces are written (FaceLabelCursor).
    ranges = detail::collect_texels(seg, num_faces, params.min_faces, std::move(results),
                                    result == TiledResult::Whole);
    // Each texel goes to the tile that owns its first face, whose halo then holds the texel.
    const int nt = static_cast<int>(seg.texels.size());
    assigned.assign(static_cast<std::size_t>(boxes.size()), {});
    reach.assign(static_cast<std::size_t>(boxes.size()), 0.0);
    // The first faces in ascending order, each looked up once.
    std::vector<int> first(static_cast<std::size_t>(nt));
    for (int t = 0; t < nt; ++t) first[t] = seg.texels[t].faces.front();
    std::vector<int> ids = first;
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    const std::vector<std::array<int, 3>> looked_up = faces_of(ids);
    for (int t = 0; t < nt; ++t) {
        const auto& f0 =
            looked_up[std::lower_bound(ids.begin(), ids.end(), first[t]) - ids.begin()];
        const int b = boxes.box_of((positions[f0[0]] + positions[f0[1]] + positions[f0[2]]) / 3.0);
        assigned[b].push_back(t);
        // How far the texel reaches out of its box, for the halo of its features part (made by
        // a whole run only).
        if (result == TiledResult::Whole)
            for (int f : seg.texels[t].faces)
                for (int v : mesh().faces[f])
                    reach[b] = std::max(reach[b], boxes.distance(b, positions[v]));
    }
    // The curvature fields over every vertex are made by the first part joined (add_features),
    // so that a job that only makes parts of this pass never holds them: 32 bytes a vertex.
    seg.curvature = CurvatureField{};
    rows.values = Eigen::MatrixXd::Zero(nt, kNumFeatures);
    rows.diameters.assign(static_cast<std::size_t>(nt), {});
    rows.no_contour.assign(static_cast<std::size_t>(nt), 0);
    rows.no_curvature.assign(static_cast<std::size_t>(nt), 0);
    start(TilePass::Features);
}

TilePart TiledSegmentation::State::depth_tile(int b) const {
    detail::TileExclusion exclude;
    if (pass == TilePass::DepthWithoutRims)
        exclude = detail::rim_exclusion({&texels[0], &texels[1]}, use, rp);
    return detail::depth_part(cutter.tile(b, depth_halo), sp, orientations, exclude,
                              pass == TilePass::Depth);
}

TilePart TiledSegmentation::State::texel_tile(int b) const {
    std::vector<const DepthMap*> maps;
    for (DetailOrientation o : orientations) maps.push_back(&depth[index_of(o)]);
    return *detail::texel_part(mesh(), maps, thresholds, tp, boxes, b,
                               kTexelHaloRadii * seg.radius);
}

// make_rims' flags counted at the vertices the tile owns; or-ed over the tiles they are the
// whole mesh's.
TilePart TiledSegmentation::State::rim_tile(int b) const {
    TilePart part;
    part.rims = detail::rim_part(make_mesh_tile(mesh(), boxes, b, depth_halo),
                                 {&texels[0], &texels[1]}, {&texel_depth[0], &texel_depth[1]}, rp);
    return part;
}

// Curvature at the texels' vertices and the texels' feature rows, for the texels the tile
// owns, with a halo that holds each texel and the curvature discs around it.
TilePart TiledSegmentation::State::feature_tile(int b) const {
    if (assigned[b].empty()) return {};
    const double rho = params.curvature_scale * seg.radius;
    // A vertex within rho of a texel's vertex along the mesh is within rho in space: the
    // slack covers the rounding of the two distances.
    const double width = std::max(depth_halo, (reach[b] + rho) * (1 + 1e-9));
    const MeshTile tile = make_mesh_tile(mesh(), boxes, b, width);
    std::optional<DepthMap> positive, negative;
    if (seg.positive_depth) positive = depth_in_tile(*seg.positive_depth, tile);
    if (seg.negative_depth) negative = depth_in_tile(*seg.negative_depth, tile);
    return detail::feature_part(tile, seg.texels, assigned[b], positive ? &*positive : nullptr,
                                negative ? &*negative : nullptr, seg.metrics.largest_side, rho);
}

void TiledSegmentation::State::add_depth(const TilePart& part) {
    const int nv = num_vertices();
    expect_depth_part(part, pass, part.tile, orientations.size(), nv);
    for (int v : part.vertices)
        expect_part(boxes.box_of(positions[v]) == part.tile, pass, part.tile,
                    "vertex " + std::to_string(v) + " is not in its box");
    std::vector<DepthMap*> maps;
    for (DetailOrientation o : orientations) {
        DepthMap& d = depth[index_of(o)];
        if (result == TiledResult::Whole && d.vertex_depth.empty())
            d.vertex_depth.assign(static_cast<std::size_t>(nv), 0.0);
        maps.push_back(&d);
    }
    if (result == TiledResult::Whole) {
        detail::add_depth_part(part, maps);
    } else {
        std::vector<double> greatest(maps.size(), 0.0);
        for (std::size_t i = 0; i < maps.size(); ++i)
            for (double x : part.depths[i]) greatest[i] = std::max(greatest[i], x);
        add_depth_summary({part.tile, greatest, part.moved, 0, 0});
    }
    if (pass == TilePass::Depth) {
        seg.num_interpolated_vertices += part.interpolated;
        seg.num_disc_samples += part.samples;
    }
}

void TiledSegmentation::State::add_depth_summary(const DepthPartSummary& part) {
    // The outputs read a map's greatest depth and moved vertices alone; the greatest is
    // set_face_depths', which starts from 0 too (so a summary's, from 0, gives the same bits).
    for (std::size_t i = 0; i < orientations.size(); ++i) {
        DepthMap& d = depth[index_of(orientations[i])];
        d.max_depth = std::max(d.max_depth, part.greatest[i]);
        d.num_moved_vertices += part.moved[i];
    }
}

void TiledSegmentation::State::add_texels(TilePart& part) {
    detail::expect_texel_part(part, pass, part.tile, orientations.size(), num_vertices(),
                              num_faces);
    if (result == TiledResult::Outputs && thresholds.empty()) thresholds = part.thresholds;
    expect_part(part.thresholds == thresholds, pass, part.tile,
                result == TiledResult::Whole
                    ? "its seed thresholds are not those of the joined depth maps"
                    : "its seed thresholds are not those of the other parts");
    for (std::size_t i = 0; i < regions.size(); ++i) {
        for (const TexelRegion& r : part.regions[i].regions)
            expect_part(boxes.box_of(positions[r.seed]) == part.tile, pass, part.tile,
                        "a region's seed is not in its box");
        if (result == TiledResult::Outputs) {
            joins[i].add(std::move(part.regions[i]), std::move(part.region_depths[i]));
            continue;
        }
        for (TexelRegion& r : part.regions[i].regions) regions[i].regions.push_back(std::move(r));
        regions[i].num_seeds += part.regions[i].num_seeds;
    }
}

void TiledSegmentation::State::add_rims(const TilePart& part) {
    detail::add_rim_part(part, part.tile, flags);
}

void TiledSegmentation::State::add_features(TilePart& part) {
    const std::size_t n = part.texels.size();
    expect_part(part.texels == assigned[part.tile], pass, part.tile,
                "its texels are not the ones whose first face it owns");
    expect_part(static_cast<std::size_t>(part.rows.values.rows()) == n &&
                    (n == 0 || part.rows.values.cols() == kNumFeatures) &&
                    part.rows.diameters.size() == n && part.rows.no_contour.size() == n &&
                    part.rows.no_curvature.size() == n,
                pass, part.tile, "its feature rows do not match its texels");
    const std::size_t m = part.curvature_vertices.size();
    expect_part(ascending_ids(part.curvature_vertices, num_vertices()) &&
                    part.curvature.gaussian.size() == m && part.curvature.mean.size() == m &&
                    part.curvature.shape_index.size() == m && part.curvature.curvedness.size() == m,
                pass, part.tile, "its curvature does not match its vertices");
    for (std::size_t k = 0; k < n; ++k) {
        const int t = part.texels[k];
        rows.values.row(t) = part.rows.values.row(static_cast<Eigen::Index>(k));
        rows.diameters[t] = std::move(part.rows.diameters[k]);
        rows.no_contour[t] = part.rows.no_contour[k];
        rows.no_curvature[t] = part.rows.no_curvature[k];
    }
    if (result == TiledResult::Outputs) return;  // no output file reads the curvature
    if (seg.curvature.gaussian.empty()) {        // the first part: NaN where no texel is
        const std::size_t nv = positions.size();
        const double nan = std::numeric_limits<double>::quiet_NaN();
        seg.curvature.gaussian.assign(nv, nan);
        seg.curvature.mean.assign(nv, nan);
        seg.curvature.shape_index.assign(nv, nan);
        seg.curvature.curvedness.assign(nv, nan);
    }
    for (std::size_t k = 0; k < m; ++k) {
        const int w = part.curvature_vertices[k];
        seg.curvature.gaussian[w] = part.curvature.gaussian[k];
        seg.curvature.mean[w] = part.curvature.mean[k];
        seg.curvature.shape_index[w] = part.curvature.shape_index[k];
        seg.curvature.curvedness[w] = part.curvature.curvedness[k];
    }
}

// The rim flags joined: for each run, the texels of the other orientation to leave out of its
// smoothing; the runs with any are smoothed again.
void TiledSegmentation::State::finish_rims() {
    std::vector<DetailOrientation> again;
    use = detail::rim_exclusions(flags, seg.runs, seg.run_excluded_texels, again);
    if (again.empty())
        begin_features();
    else
        begin_depth(TilePass::DepthWithoutRims, std::move(again));
}

std::string tile_numbers(const std::vector<int>& tiles) {
    std::string list;
    for (std::size_t k = 0; k < tiles.size() && k < 10; ++k)
        list += (k ? ", " : "") + std::to_string(tiles[k] + 1);
    if (tiles.size() > 10) list += " and " + std::to_string(tiles.size() - 10) + " more";
    return list;
}

TiledSegmentation::TiledSegmentation(const Mesh& mesh, const SegmentationParams& params, int tiles,
                                     TiledResult result)
    : state_(std::make_unique<State>(mesh, params, result)) {
    if (mesh.num_faces() == 0) throw InvalidInput("segmentation: the mesh has no face");
    check_segmentation_params(params);
    // The metrics' arrays (normals and areas, about 24 bytes a face) only for the result: the
    // passes need the extent alone.
    state_->begin(make_mesh_extent(mesh), tiles);
}

TiledSegmentation::TiledSegmentation(const MeshOutline& outline, const SegmentationParams& params,
                                     int tiles) {
    if (!outline.faces)
        throw std::invalid_argument("TiledSegmentation: the outline cannot look up its faces");
    state_ = std::make_unique<State>(outline, params);
    if (state_->num_faces == 0) throw InvalidInput("segmentation: the mesh has no face");
    check_segmentation_params(params);
    state_->begin(outline.extent, tiles);
}

// What every run sets up before its first pass, from the mesh's positions and extent.
void TiledSegmentation::State::begin(const MeshMetrics& extent, int tiles) {
    if (std::abs(make_unit_frame(positions).exponent) > 32)
        throw InvalidInput(
            "tiles: the mesh's size is beyond 2^32 or below 2^-32 units; scale it "
            "first or segment it whole");
    boxes = make_tile_boxes(positions, tiles);
    seg.metrics = extent;
    seg.radius = resolve_radius(params, seg.metrics.largest_side);
    if (auto d = detail::radius_diagnostic(seg.radius, seg.metrics.mean_edge_length))
        seg.diagnostics.push_back(std::move(*d));
    seg.runs = detail::orientations_of(params.orientation);
    seg.run_excluded_texels.assign(seg.runs.size(), 0);
    sp = detail::smoothing_params(params, seg.radius);
    tp = detail::texel_params(params, seg.radius);
    rp = detail::rim_params(seg.radius);
    depth_halo = kDepthHaloRadii * seg.radius;
    cutter.set_run(boxes, sp, seg.radius);
    begin_depth(TilePass::Depth, first_depth_orientations(params));
}

TiledSegmentation::~TiledSegmentation() = default;
TiledSegmentation::TiledSegmentation(TiledSegmentation&&) noexcept = default;
TiledSegmentation& TiledSegmentation::operator=(TiledSegmentation&&) noexcept = default;

int TiledSegmentation::num_tiles() const { return state_->boxes.size(); }

namespace {

// Refuses a tile that `boxes` do not have.
void expect_tile(const TileBoxes& boxes, int tile) {
    if (tile < 0 || tile >= boxes.size())
        throw InvalidInput("tiles: tile " + std::to_string(tile + 1) + " is not in 1 to " +
                           std::to_string(boxes.size()));
}

}  // namespace

DepthTile TiledSegmentation::depth_tile(int tile) const {
    expect_tile(state_->boxes, tile);
    return state_->cutter.tile_of_all(tile, kTileMeshHaloRadii * state_->seg.radius);
}

void TiledSegmentation::spool_depth_tile(
    int tile, const std::string& scratch_dir,
    const std::function<void(const DepthTile& numbers, const DepthTileRows& rows)>& use) const {
    expect_tile(state_->boxes, tile);
    state_->cutter.spool(tile, kTileMeshHaloRadii * state_->seg.radius, scratch_dir, use);
}

TilePass TiledSegmentation::pass() const { return state_->pass; }

const std::vector<DetailOrientation>& TiledSegmentation::orientations() const {
    return state_->orientations;
}

TilePart TiledSegmentation::run_tile(int tile) const {
    const State& s = *state_;
    if (s.result == TiledResult::Outputs)
        throw InvalidInput("tiles: a run kept for its outputs joins parts; it makes none");
    expect_tile(s.boxes, tile);
    TilePart part;
    switch (s.pass) {
        case TilePass::Depth:
        case TilePass::DepthWithoutRims:
            part = s.depth_tile(tile);
            break;
        case TilePass::Texels:
        case TilePass::TexelsWithoutRims:
            part = s.texel_tile(tile);
            break;
        case TilePass::Rims:
            part = s.rim_tile(tile);
            break;
        case TilePass::Features:
            part = s.feature_tile(tile);
            break;
        case TilePass::Done:
            throw InvalidInput("tiles: the segmentation is complete");
    }
    part.pass = s.pass;
    part.tile = tile;
    return part;
}

void TiledSegmentation::State::expect_outputs_at(bool right_pass, const std::string& what) const {
    if (result != TiledResult::Outputs)
        throw InvalidInput("tiles: only a run kept for its outputs takes " + what);
    if (!right_pass)
        throw InvalidInput("tiles: " + what + ", but the run waits for pass " + name_of(pass));
}

void TiledSegmentation::State::expect_awaited(TilePass of, int tile) const {
    if (tile < 0 || tile >= boxes.size())
        throw InvalidInput("tiles: a part of tile " + std::to_string(tile + 1) + ", not in 1 to " +
                           std::to_string(boxes.size()));
    expect_part(of == pass, of, tile, std::string("the run waits for pass ") + name_of(pass));
    expect_part(!added[tile], of, tile, "the tile's part is in already");
}

void TiledSegmentation::add_depth_summary(const DepthPartSummary& summary) {
    State& s = *state_;
    s.expect_outputs_at(is_depth_pass(s.pass), "a depth part's summary");
    s.expect_awaited(s.pass, summary.tile);
    const std::size_t n = s.orientations.size();
    expect_part(summary.greatest.size() == n && summary.moved.size() == n, s.pass, summary.tile,
                "its summary has the counts of " + std::to_string(summary.greatest.size()) +
                    " orientations, not " + std::to_string(n));
    s.add_depth_summary(summary);
    if (s.pass == TilePass::Depth) {
        s.seg.num_interpolated_vertices += summary.interpolated;
        s.seg.num_disc_samples += summary.samples;
    }
    s.added[summary.tile] = 1;
}

void TiledSegmentation::add(TilePart part) {
    State& s = *state_;
    s.expect_awaited(part.pass, part.tile);
    switch (s.pass) {
        case TilePass::Depth:
        case TilePass::DepthWithoutRims:
            s.add_depth(part);
            break;
        case TilePass::Texels:
        case TilePass::TexelsWithoutRims:
            s.add_texels(part);
            break;
        case TilePass::Rims:
            s.add_rims(part);
            break;
        case TilePass::Features:
            s.add_features(part);
            break;
        case TilePass::Done:
            break;
    }
    s.added[part.tile] = 1;
}

std::vector<int> TiledSegmentation::missing() const {
    std::vector<int> out;
    for (std::size_t b = 0; b < state_->added.size(); ++b)
        if (!state_->added[b]) out.push_back(static_cast<int>(b));
    return out;
}

void TiledSegmentation::finish_pass() {
    State& s = *state_;
    if (s.pass == TilePass::Done) return;
    const std::vector<int> absent = missing();
    if (!absent.empty())
        throw InvalidInput(std::string("tiles: pass ") + name_of(s.pass) + " lacks the part of " +
                           (absent.size() == 1 ? "tile " : "tiles ") + tile_numbers(absent));
    switch (s.pass) {
        case TilePass::Depth:
        case TilePass::DepthWithoutRims:
            if (s.result == TiledResult::Whole)
                for (DetailOrientation o : s.orientations)
                    set_face_depths(s.mesh(), s.depth[index_of(o)]);
            s.begin_texels(s.pass == TilePass::Depth ? TilePass::Texels
                                                     : TilePass::TexelsWithoutRims);
            break;
        case TilePass::Texels:
        case TilePass::TexelsWithoutRims:
            for (std::size_t i = 0; i < s.orientations.size(); ++i) {
                const std::size_t o = index_of(s.orientations[i]);
                s.texels[o] = s.result == TiledResult::Whole
                                  ? detail::merge_tile_regions(std::move(s.regions[i]), s.depth[o],
                                                               s.tp, s.thresholds[i])
                                  : s.joins[i].merge(s.tp, s.orientations[i], s.thresholds[i],
                                                     s.texel_depth[o]);
            }
            s.finish_texels();
            break;
        case TilePass::Rims:
            s.finish_rims();
            break;
        case TilePass::Features:
            s.seg.features = normalise_feature_rows(std::move(s.rows));
            for (const auto& d : s.seg.features.diagnostics) s.seg.diagnostics.push_back(d);
            detail::cluster_textures(s.seg, s.num_faces, s.ranges, s.params.clustering);
            if (s.result == TiledResult::Whole) s.seg.metrics = make_mesh_metrics(s.mesh());
            s.start(TilePass::Done);
            break;
        case TilePass::Done:
            break;
    }
}

void TiledSegmentation::finish_texel_pass(std::array<TexelSet, 2> texels) {
    State& s = *state_;
    s.expect_outputs_at(is_texel_pass(s.pass), "texels joined elsewhere");
    if (std::find(s.added.begin(), s.added.end(), 1) != s.added.end())
        throw InvalidInput(std::string("tiles: texels joined elsewhere, but a part of pass ") +
                           name_of(s.pass) + " is in already");
    for (DetailOrientation d : s.orientations) {
        const std::size_t o = index_of(d);
        for (const Texel& t : texels[o].texels)  // faces ascend: the last is the greatest
            if (t.orientation != d || t.faces.empty() || t.faces.front() < 0 ||
                t.faces.back() >= s.num_faces)
                throw InvalidInput(
                    "tiles: a joined texel is not of its orientation, or its faces are not the "
                    "mesh's");
        s.texels[o] = std::move(texels[o]);
    }
    s.finish_texels();
}

Segmentation TiledSegmentation::result() && {
    if (state_->pass != TilePass::Done)
        throw InvalidInput(std::string("tiles: the segmentation waits for pass ") +
                           name_of(state_->pass));
    return std::move(state_->seg);
}

Segmentation run_tiled_segmentation(const Mesh& mesh, const SegmentationParams& params, int tiles,
                                    const StageObserver& observer) {
    TiledSegmentation run(mesh, params, tiles);
    while (run.pass() != TilePass::Done) {
        const std::string stage = stage_of(run.pass());
        detail::timed(observer, stage, [&] {
            for (int b = 0; b < run.num_tiles(); ++b) {
                // Which tile a long pass is at: a stage begun, never ended, so that a terminal
                // shows it in place and a log gets the pass's line alone.
                if (observer)
                    observer({stage + ": tile " + std::to_string(b + 1) + "/" +
                                  std::to_string(run.num_tiles()),
                              -1.0});
                run.add(run.run_tile(b));
            }
            run.finish_pass();
        });
    }
    return std::move(run).result();
}

}  // namespace geotex
