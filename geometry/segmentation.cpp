#include "geometry/segmentation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"
#include "geometry/detail/segmentation_steps.hpp"
#include "geometry/rims.hpp"
#include "geometry/unit_frame.hpp"

namespace geotex {

using detail::timed;

void check_segmentation_params(const SegmentationParams& p) {
    const auto fail = [](const std::string& what) {
        throw InvalidInput("segmentation parameters: " + what);
    };
    const auto in_unit = [](double v) { return v >= 0 && v <= 1; };
    if (p.radius != 0) {
        if (!(p.radius > 0) || !std::isfinite(p.radius))
            fail("the radius must be positive and finite (got " + std::to_string(p.radius) + ")");
    } else if (!(p.radius_rel > 0 && p.radius_rel < 1)) {
        fail("radius_rel must be in (0, 1), a fraction of the largest bounding-box side (got " +
             std::to_string(p.radius_rel) + ")");
    }
    if (!in_unit(p.curvature_scale))
        fail("curvature_scale must be in [0, 1] (got " + std::to_string(p.curvature_scale) + ")");
    if (!in_unit(p.merge_overlap))
        fail("merge_overlap must be in [0, 1] (got " + std::to_string(p.merge_overlap) + ")");
    if (!(p.min_depth_rel >= 0) || !std::isfinite(p.min_depth_rel))
        fail("min_depth_rel must be >= 0 and finite (got " + std::to_string(p.min_depth_rel) + ")");
    if (p.min_faces < 1)
        fail("min_faces must be at least 1 (got " + std::to_string(p.min_faces) + ")");
    check_clustering_params(p.clustering);
}

double resolve_radius(const SegmentationParams& params, double largest_side) {
    if (params.radius != 0) {
        if (!(params.radius > 0) || !std::isfinite(params.radius))
            throw InvalidInput("the radius must be positive and finite (got " +
                               std::to_string(params.radius) + ")");
        return params.radius;
    }
    if (!(params.radius_rel > 0 && params.radius_rel < 1))
        throw InvalidInput(
            "the scale must be in (0, 1), a fraction of the largest bounding-box side (got " +
            std::to_string(params.radius_rel) + ")");
    return params.radius_rel * largest_side;
}

namespace {

// Multiplies every length-valued result by 2^exponent (areas by its square, curvatures by
// its inverse): back from the unit frame to mesh units. Exact, as the scaling was, unless
// a value leaves the range of doubles (the area of a mesh 1e300 wide is infinite in its
// own unit). Features are computed on the unit-side mesh and do not change.
void to_mesh_units(Segmentation& seg, int exponent) {
    const auto length = [&](double& x) { x = std::ldexp(x, exponent); };
    const auto area = [&](double& x) { x = std::ldexp(x, 2 * exponent); };
    seg.radius = std::ldexp(seg.radius, exponent);
    for (double& a : seg.metrics.face_area) area(a);
    for (double& a : seg.metrics.vertex_area) area(a);
    for (int axis = 0; axis < 3; ++axis) {
        length(seg.metrics.bbox_min[axis]);
        length(seg.metrics.bbox_max[axis]);
    }
    length(seg.metrics.largest_side);
    length(seg.metrics.mean_edge_length);
    for (double& k : seg.curvature.gaussian) k = std::ldexp(k, -2 * exponent);
    for (double& k : seg.curvature.mean) k = std::ldexp(k, -exponent);
    for (double& k : seg.curvature.curvedness) k = std::ldexp(k, -exponent);
    for (auto* depth : {&seg.positive_depth, &seg.negative_depth})
        if (*depth) {
            for (double& d : (*depth)->vertex_depth) length(d);
            for (double& d : (*depth)->face_depth) length(d);
            length((*depth)->max_depth);
        }
    for (auto& set : seg.texel_sets) length(set.global_threshold);
    for (auto& t : seg.texels) {
        length(t.threshold);
        length(t.depth_mean);
        length(t.depth_std);
    }
}

Segmentation run_in_unit_frame(const Mesh& mesh, const MeshTopology& topology,
                               const MeshMetrics& metrics, const DepthMapper& depth_mapper,
                               const SegmentationParams& params, const StageObserver& observer);

}  // namespace

SegmentationContext::SegmentationContext(const Mesh& mesh, const StageObserver& observer)
    : mesh_(&mesh) {
    if (mesh.num_faces() == 0) throw InvalidInput("segmentation: the mesh has no face");
    // Meshes whose size is far from 1 are brought near it by a power of two first: squared
    // lengths, areas and quadric fits over r^4 overflow or underflow beyond about 1e+-75.
    // Within 2^+-32 the pipeline is run on the mesh as it is: no copy, and the results are
    // those of the mesh's own coordinates.
    const UnitFrame frame = make_unit_frame(mesh.positions);
    if (std::abs(frame.exponent) > 32) {
        exponent_ = frame.exponent;
        unit_mesh_ = mesh;
        for (auto& p : unit_mesh_->positions)
            for (int axis = 0; axis < 3; ++axis) p[axis] = std::ldexp(p[axis], -exponent_);
    }
    const Mesh& run_mesh = unit_mesh_ ? *unit_mesh_ : mesh;
    timed(observer, "topology", [&] {
        topology_ = make_topology(run_mesh);
        metrics_ = make_mesh_metrics(run_mesh, topology_);
        depth_mapper_.emplace(run_mesh);
    });
}

Segmentation SegmentationContext::run_without_shared(const SegmentationParams& params,
                                                     const StageObserver& observer) const {
    check_segmentation_params(params);
    SegmentationParams unit_params = params;
    unit_params.radius = std::ldexp(params.radius, -exponent_);
    return run_in_unit_frame(unit_mesh_ ? *unit_mesh_ : *mesh_, topology_, metrics_, *depth_mapper_,
                             unit_params, observer);
}

Segmentation SegmentationContext::run(const SegmentationParams& params,
                                      const StageObserver& observer) const& {
    Segmentation seg = run_without_shared(params, observer);
    seg.topology = topology_;
    seg.metrics = metrics_;
    if (exponent_ != 0) to_mesh_units(seg, exponent_);
    return seg;
}

Segmentation SegmentationContext::run(const SegmentationParams& params,
                                      const StageObserver& observer) && {
    Segmentation seg = run_without_shared(params, observer);
    seg.topology = std::move(topology_);
    seg.metrics = std::move(metrics_);
    depth_mapper_.reset();
    unit_mesh_.reset();
    if (exponent_ != 0) to_mesh_units(seg, exponent_);
    return seg;
}

Segmentation SegmentationContext::run_without_topology(const SegmentationParams& params,
                                                       const StageObserver& observer) const {
    Segmentation seg = run_without_shared(params, observer);
    if (exponent_ != 0) to_mesh_units(seg, exponent_);
    return seg;
}

Segmentation run_segmentation(const Mesh& mesh, const SegmentationParams& params,
                              const StageObserver& observer) {
    if (mesh.num_faces() == 0) throw InvalidInput("segmentation: the mesh has no face");
    check_segmentation_params(params);  // before the topology, which takes a while
    return SegmentationContext(mesh, observer).run(params, observer);
}

namespace {

// The results of one orientation between the steps of a run: its depth map and texels (the
// latest pass's), and its second smoothing when rims were left out of it.
struct OrientationRun {
    std::optional<DepthMap> depth;
    std::optional<TexelSet> texels;
    std::optional<SmoothedSurface> without_rims;
};

// What the steps of one run share: the input, the parameters and the results so far.
struct Run {
    const Mesh& mesh;
    const MeshTopology& topology;
    const MeshMetrics& metrics;
    const DepthMapper& depth_mapper;
    const SegmentationParams& params;
    const StageObserver& observer;
    Segmentation& seg;
    TexelParams texel_params;
    OrientationRun positive;
    OrientationRun negative;

    OrientationRun& of(DetailOrientation o) {
        return o == DetailOrientation::Positive ? positive : negative;
    }
};

DetailOrientation opposite(DetailOrientation o) {
    return o == DetailOrientation::Positive ? DetailOrientation::Negative
                                            : DetailOrientation::Positive;
}

// The radius in mesh units, with a diagnostic when it is too small for the mesh.
void measure_radius(Run& run) {
    Segmentation& seg = run.seg;
    seg.radius = resolve_radius(run.params, run.metrics.largest_side);
    if (auto d = detail::radius_diagnostic(seg.radius, run.metrics.mean_edge_length))
        seg.diagnostics.push_back(std::move(*d));
    run.texel_params = detail::texel_params(run.params, seg.radius);
}

// The first smoothing (paper §3.1), by `smoother`, which is set up here.
SmoothedSurface smooth(Run& run, std::optional<SurfaceSmoother>& smoother) {
    const SmoothedSurface smoothed = timed(run.observer, "smoothing", [&] {
        smoother.emplace(run.mesh, run.topology, run.metrics,
                         detail::smoothing_params(run.params, run.seg.radius));
        return smoother->smooth();
    });
    run.seg.num_interpolated_vertices = smoothed.num_interpolated_vertices;
    run.seg.num_disc_samples = smoothed.num_samples;
    return smoothed;
}

// Depth maps and texels of the orientations in `which`, each from surface(o); two at a time
// in parallel (the texels' region growing is serial).
template <class Surface>
void depth_and_texels(Run& run, const std::vector<DetailOrientation>& which,
                      const std::string& suffix, Surface&& surface) {
    auto depth = [&](DetailOrientation o) {
        OrientationRun& r = run.of(o);
        r.texels.reset();  // a second pass: the first one's go first
        r.depth.reset();
        r.depth = run.depth_mapper.map(run.metrics.vertex_normal, surface(o), o);
    };
    auto texels = [&](DetailOrientation o) {
        OrientationRun& r = run.of(o);
        r.texels = make_texels(run.mesh, run.topology, *r.depth, run.texel_params);
    };
    if (which.size() == 1) {
        const std::string name = std::string(name_of(which[0])) + suffix;
        timed(run.observer, "depth map (" + name + ")", [&] { depth(which[0]); });
        timed(run.observer, "texels (" + name + ")", [&] { texels(which[0]); });
    } else if (which.size() == 2) {
        timed(run.observer, "depth maps (positive, negative" + suffix + ")",
              [&] { detail::parallel_invoke([&] { depth(which[0]); }, [&] { depth(which[1]); }); });
        timed(run.observer, "texels (positive, negative" + suffix + ")", [&] {
            detail::parallel_invoke([&] { texels(which[0]); }, [&] { texels(which[1]); });
        });
    }
}

// Whether a texel of one orientation asked for may raise a rim in the other (docs/rims.md).
bool rims_wanted(Run& run, const SmoothedSurface& smoothed) {
    for (DetailOrientation o : run.seg.runs) {
        const OrientationRun& r = run.of(o);
        if (rims_possible(run.mesh, run.topology, run.metrics.vertex_normal, smoothed, *r.texels,
                          *r.depth, detail::rim_params(run.seg.radius)))
            return true;
    }
    return false;
}

// Rim removal (docs/rims.md): the details of the other orientation are left out of a second
// smoothing, so that they no longer drag the smoothed surface and raise rims. Needs the depth
// maps and texels of both orientations; keeps those of the runs asked for only.
void smooth_without_rims(Run& run, const SurfaceSmoother& smoother) {
    Segmentation& seg = run.seg;
    const Rims rims = timed(run.observer, "rims", [&] {
        return make_rims(run.mesh, run.topology, *run.positive.texels, *run.positive.depth,
                         *run.negative.texels, *run.negative.depth,
                         detail::rim_params(run.seg.radius));
    });
    for (std::size_t r = 0; r < seg.runs.size(); ++r) {
        const bool positive = seg.runs[r] == DetailOrientation::Positive;
        const std::vector<char>& excluded =
            positive ? rims.exclude_for_positive : rims.exclude_for_negative;
        if (excluded.empty()) continue;
        seg.run_excluded_texels[r] =
            positive ? rims.num_excluded_for_positive : rims.num_excluded_for_negative;
        run.of(seg.runs[r]).without_rims = timed(
            run.observer, "smoothing (" + std::string(name_of(seg.runs[r])) + ", without rims)",
            [&] { return smoother.smooth(excluded); });
    }
    if (seg.runs.size() == 1) {  // the other orientation was only needed to find the rims
        OrientationRun& other = run.of(opposite(seg.runs[0]));
        other.depth.reset();
        other.texels.reset();
    }
}

// Depth maps and texels again for the runs smoothed a second time.
void redo_without_rims(Run& run) {
    std::vector<DetailOrientation> again;
    for (DetailOrientation o : run.seg.runs)
        if (run.of(o).without_rims) again.push_back(o);
    depth_and_texels(
        run, again, ", without rims",
        [&](DetailOrientation o) -> const SmoothedSurface& { return *run.of(o).without_rims; });
    run.positive.without_rims.reset();
    run.negative.without_rims.reset();
}

// Moves the texels of every run into seg.texels (detail::collect_texels).
std::vector<std::pair<int, int>> collect_texels(Run& run) {
    std::vector<detail::OrientationResult> results;
    for (DetailOrientation o : run.seg.runs) {
        OrientationRun& r = run.of(o);
        results.push_back({o, std::move(*r.depth), std::move(*r.texels)});
        r.depth.reset();
        r.texels.reset();
    }
    return detail::collect_texels(run.seg, run.mesh.num_faces(), run.params.min_faces,
                                  std::move(results));
}

// Curvatures at the vertices of texels (paper §3.3).
void texel_curvature(Run& run) {
    Segmentation& seg = run.seg;
    seg.curvature = timed(run.observer, "curvature", [&] {
        CurvatureParams cp;
        cp.radius = run.params.curvature_scale * seg.radius;
        cp.only.assign(static_cast<std::size_t>(run.mesh.num_vertices()), 0);  // texel vertices
        for (int f = 0; f < run.mesh.num_faces(); ++f)
            if (seg.face_texel[f] >= 0)
                for (int v : run.mesh.faces[f]) cp.only[v] = 1;
        return make_curvature(run.mesh, run.topology, run.metrics.vertex_normal, cp);
    });
}

// The feature table of the texels (paper §3.3).
void texel_features(Run& run) {
    Segmentation& seg = run.seg;
    seg.features = timed(run.observer, "features", [&] {
        FeatureInputs in;
        in.mesh = &run.mesh;
        in.topology = &run.topology;
        in.curvature = &seg.curvature;
        in.positive_depth = seg.positive_depth ? &*seg.positive_depth : nullptr;
        in.negative_depth = seg.negative_depth ? &*seg.negative_depth : nullptr;
        in.largest_side = run.metrics.largest_side;
        return make_feature_table(in, seg.texels);
    });
    for (const auto& d : seg.features.diagnostics) seg.diagnostics.push_back(d);
}

// The textures (paper §3.4, detail::cluster_textures).
void cluster_textures(Run& run, const std::vector<std::pair<int, int>>& run_texel_range) {
    timed(run.observer, "clustering", [&] {
        detail::cluster_textures(run.seg, run.mesh.num_faces(), run_texel_range,
                                 run.params.clustering);
    });
}

Segmentation run_in_unit_frame(const Mesh& mesh, const MeshTopology& topology,
                               const MeshMetrics& metrics, const DepthMapper& depth_mapper,
                               const SegmentationParams& params, const StageObserver& observer) {
    Segmentation seg;
    Run run{mesh, topology, metrics, depth_mapper, params, observer, seg, {}, {}, {}};
    measure_radius(run);
    // The smoother is kept for the second smoothing of the rim removal and released as soon
    // as it is done (its recorded discs are the largest buffer of the pipeline).
    std::optional<SurfaceSmoother> smoother;
    // Released once the depth maps no longer need it: 24 bytes a vertex.
    std::optional<SmoothedSurface> smoothed = smooth(run, smoother);
    seg.runs = detail::orientations_of(params.orientation);
    if (!params.remove_rims) smoother.reset();
    const auto first_surface = [&](DetailOrientation) -> const SmoothedSurface& {
        return *smoothed;
    };
    depth_and_texels(run, seg.runs, "", first_surface);

    // With one orientation asked, the other is computed only when one of its texels may be
    // deeper than one of ours.
    seg.run_excluded_texels.assign(seg.runs.size(), 0);
    if (params.remove_rims &&
        timed(run.observer, "rim check", [&] { return rims_wanted(run, *smoothed); })) {
        if (seg.runs.size() == 1) depth_and_texels(run, {opposite(seg.runs[0])}, "", first_surface);
        smoothed.reset();
        smooth_without_rims(run, *smoother);
    }
    smoothed.reset();
    smoother.reset();
    redo_without_rims(run);

    const std::vector<std::pair<int, int>> run_texel_range = collect_texels(run);
    texel_curvature(run);
    texel_features(run);
    cluster_textures(run, run_texel_range);
    return seg;
}

}  // namespace

namespace detail {

std::vector<DetailOrientation> orientations_of(OrientationMode mode) {
    std::vector<DetailOrientation> runs;
    if (mode != OrientationMode::Negative) runs.push_back(DetailOrientation::Positive);
    if (mode != OrientationMode::Positive) runs.push_back(DetailOrientation::Negative);
    return runs;
}

SmoothingParams smoothing_params(const SegmentationParams& params, double radius) {
    SmoothingParams sp;
    sp.radius = radius;
    sp.method = params.smoothing;
    sp.area_weighted = params.area_weighted;
    sp.disc = params.disc;
    return sp;
}

TexelParams texel_params(const SegmentationParams& params, double radius) {
    TexelParams tp;
    tp.radius = radius;
    tp.merge_overlap = params.merge_overlap;
    tp.min_depth_rel = params.min_depth_rel;
    tp.min_faces = params.min_faces;
    return tp;
}

// The paper's radius; the rims' other fields keep their defaults.
RimParams rim_params(double radius) {
    RimParams rp;
    rp.radius = radius;
    return rp;
}

std::optional<Diagnostic> radius_diagnostic(double radius, double mean_edge_length) {
    // A disc needs a few rings of vertices for its mean to mean anything: below about three
    // edge lengths the depth is dominated by the triangulation itself. The ratio, not the
    // two lengths, goes into the message: they may be in the unit frame.
    if (!(radius < 3 * mean_edge_length)) return std::nullopt;
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.3g", radius / mean_edge_length);
    return Diagnostic{"segmentation",
                      std::string("the radius is less than three mean edge lengths (") + ratio +
                          " of them): the discs hold too few vertices and the texels follow the "
                          "triangulation; use a larger scale or a finer mesh"};
}

std::vector<std::pair<int, int>> collect_texels(Segmentation& seg, int num_faces, int min_faces,
                                                std::vector<OrientationResult> runs,
                                                bool face_labels) {
    // The faces taken by a texel so far: a bit a face, so that a join that writes no labels
    // holds none.
    std::vector<bool> taken(static_cast<std::size_t>(num_faces), false);
    std::vector<std::pair<int, int>> run_texel_range;
    for (OrientationResult& r : runs) {
        const std::string name = name_of(r.orientation);
        TexelSet set = std::move(r.texels);
        const int first = static_cast<int>(seg.texels.size());
        int num_dropped = 0;
        for (auto& t : set.texels) {
            std::vector<int> kept;
            for (int f : t.faces)
                if (!taken[f]) kept.push_back(f);
            if (static_cast<int>(kept.size()) < min_faces) {
                ++num_dropped;
                continue;
            }
            t.faces = std::move(kept);
            for (int f : t.faces) taken[f] = true;
            seg.texels.push_back(std::move(t));
        }
        if (num_dropped > 0)
            seg.diagnostics.push_back(
                {"segmentation", std::to_string(num_dropped) + " " + name +
                                     " texels lay inside texels of the other orientation"});
        for (const auto& d : set.diagnostics) seg.diagnostics.push_back(d);
        set.texels.clear();
        seg.texel_sets.push_back(std::move(set));
        run_texel_range.emplace_back(first, static_cast<int>(seg.texels.size()));
        (r.orientation == DetailOrientation::Positive ? seg.positive_depth : seg.negative_depth) =
            std::move(r.depth);
    }
    if (face_labels) {
        seg.face_texel.assign(static_cast<std::size_t>(num_faces), -1);
        for (std::size_t i = 0; i < seg.texels.size(); ++i)
            for (int f : seg.texels[i].faces) seg.face_texel[f] = static_cast<int>(i);
    }
    return run_texel_range;
}

void cluster_textures(Segmentation& seg, int num_faces,
                      const std::vector<std::pair<int, int>>& run_texel_range,
                      const ClusteringParams& params) {
    // The orientations are clustered apart, and side by side: the bulk of a clustering of many
    // texels, Eigen's tridiagonalisation, runs on one core.
    std::vector<ClusteringResult> clusterings(seg.runs.size());
    const auto cluster_run = [&](std::size_t r) {
        const auto [first, last] = run_texel_range[r];
        clusterings[r] = make_clustering(
            seg.features.values.block(first, 0, last - first, kNumClusteringFeatures), params);
    };
    if (clusterings.size() == 2)
        parallel_invoke([&] { cluster_run(0); }, [&] { cluster_run(1); });
    else
        for (std::size_t r = 0; r < clusterings.size(); ++r) cluster_run(r);

    seg.texel_texture.assign(seg.texels.size(), -1);
    for (std::size_t r = 0; r < seg.runs.size(); ++r) {
        const auto [first, last] = run_texel_range[r];
        ClusteringResult& c = clusterings[r];
        for (int i = first; i < last; ++i)
            seg.texel_texture[i] = seg.num_textures + c.labels[i - first];
        for (int k = 0; k < c.num_clusters; ++k) seg.texture_orientation.push_back(seg.runs[r]);
        seg.num_textures += c.num_clusters;
        for (const auto& d : c.diagnostics) seg.diagnostics.push_back(d);
        seg.clusterings.push_back(std::move(c));
    }
    if (seg.face_texel.empty()) return;  // collect_texels made no labels
    seg.face_texture.assign(num_faces, -1);
    for (int f = 0; f < num_faces; ++f)
        if (seg.face_texel[f] >= 0) seg.face_texture[f] = seg.texel_texture[seg.face_texel[f]];
}

}  // namespace detail

FaceLabelCursor::FaceLabelCursor(const Segmentation& seg) : seg_(seg) {
    std::size_t n = 0;
    for (const Texel& t : seg.texels) n += t.faces.size();
    face_texel_.reserve(n);
    for (std::size_t i = 0; i < seg.texels.size(); ++i)
        for (int f : seg.texels[i].faces) face_texel_.emplace_back(f, static_cast<int>(i));
    std::sort(face_texel_.begin(), face_texel_.end());
    for (std::size_t k = 1; k < face_texel_.size(); ++k)
        if (face_texel_[k].first == face_texel_[k - 1].first)
            throw InvalidInput("segmentation: face " + std::to_string(face_texel_[k].first) +
                               " is in two texels");
}

void FaceLabelCursor::next(int first, int count, std::vector<int>& texel,
                           std::vector<int>& texture) {
    texel.assign(static_cast<std::size_t>(count), -1);
    texture.assign(static_cast<std::size_t>(count), -1);
    while (at_ < face_texel_.size() && face_texel_[at_].first < first) ++at_;
    for (; at_ < face_texel_.size() && face_texel_[at_].first < first + count; ++at_) {
        const auto [f, t] = face_texel_[at_];
        texel[f - first] = t;
        texture[f - first] = seg_.texel_texture[t];
    }
}

}  // namespace geotex
