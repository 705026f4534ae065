#include "geometry/segmentation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "geometry/detail/parallel.hpp"
#include "geometry/errors.hpp"
#include "geometry/rims.hpp"
#include "geometry/unit_frame.hpp"

namespace geotex {

namespace {

// Times a stage and tells the observer before and after.
template <class Fn>
auto timed(const StageObserver& observer, const std::string& stage, Fn&& fn) {
    if (observer) observer({stage, -1.0});
    const auto start = std::chrono::steady_clock::now();
    auto finish = [&] {
        if (observer)
            observer({stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    };
    if constexpr (std::is_void_v<decltype(fn())>) {
        fn();
        finish();
    } else {
        auto result = fn();
        finish();
        return result;
    }
}

const char* orientation_name(DetailOrientation o) { return o == DetailOrientation::Positive ? "positive" : "negative"; }

}  // namespace

double resolve_radius(const SegmentationParams& params, double largest_side) {
    if (params.radius != 0) {
        if (!(params.radius > 0) || !std::isfinite(params.radius))
            throw InvalidInput("the radius must be positive and finite (got " + std::to_string(params.radius) + ")");
        return params.radius;
    }
    if (!(params.radius_rel > 0 && params.radius_rel < 1))
        throw InvalidInput("the scale must be in (0, 1), a fraction of the largest bounding-box side (got " +
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

Segmentation run_in_unit_frame(const Mesh& mesh, const SegmentationParams& params, const StageObserver& observer);

}  // namespace

Segmentation run_segmentation(const Mesh& mesh, const SegmentationParams& params, const StageObserver& observer) {
    if (mesh.num_faces() == 0) throw InvalidInput("segmentation: the mesh has no face");
    // Meshes whose size is far from 1 are brought near it by a power of two first: squared
    // lengths, areas and quadric fits over r^4 overflow or underflow beyond about 1e+-75.
    // Within 2^+-32 the pipeline is run on the mesh as it is (no copy; every result the
    // same bits as before this frame existed).
    const UnitFrame frame = make_unit_frame(mesh.positions);
    if (std::abs(frame.exponent) <= 32) return run_in_unit_frame(mesh, params, observer);
    Mesh unit = mesh;
    for (auto& p : unit.positions)
        for (int axis = 0; axis < 3; ++axis) p[axis] = std::ldexp(p[axis], -frame.exponent);
    SegmentationParams unit_params = params;
    unit_params.radius = std::ldexp(params.radius, -frame.exponent);
    Segmentation seg = run_in_unit_frame(unit, unit_params, observer);
    unit = Mesh();
    to_mesh_units(seg, frame.exponent);
    return seg;
}

namespace {

Segmentation run_in_unit_frame(const Mesh& mesh, const SegmentationParams& params, const StageObserver& observer) {
    Segmentation seg;
    timed(observer, "topology", [&] {
        seg.topology = make_topology(mesh);
        seg.metrics = make_mesh_metrics(mesh, seg.topology);
    });
    seg.radius = resolve_radius(params, seg.metrics.largest_side);
    // A disc needs a few rings of vertices for its mean to mean anything: below about three
    // edge lengths the depth is dominated by the triangulation itself.
    // The ratio, not the two lengths, goes into the message: they are in the unit frame here.
    if (seg.radius < 3 * seg.metrics.mean_edge_length) {
        char ratio[32];
        std::snprintf(ratio, sizeof ratio, "%.3g", seg.radius / seg.metrics.mean_edge_length);
        seg.diagnostics.push_back({"segmentation", std::string("the radius is less than three mean edge lengths (") +
                                                       ratio +
                                                       " of them): the discs hold too few vertices and the texels "
                                                       "follow the triangulation; use a larger scale or a finer mesh"});
    }

    // The smoother is kept for the second smoothing of the rim removal and released as soon
    // as it is done (its recorded discs are the largest buffer of the pipeline).
    std::optional<SurfaceSmoother> smoother;
    const SmoothedSurface smoothed = timed(observer, "smoothing", [&] {
        SmoothingParams sp;
        sp.radius = seg.radius;
        sp.method = params.smoothing;
        sp.area_weighted = params.area_weighted;
        sp.disc = params.disc;
        smoother.emplace(mesh, seg.topology, seg.metrics, sp);
        return smoother->smooth();
    });
    seg.num_interpolated_vertices = smoothed.num_interpolated_vertices;
    seg.num_disc_samples = smoothed.num_samples;
    std::vector<DetailOrientation>& runs = seg.runs;
    if (params.orientation != OrientationMode::Negative) runs.push_back(DetailOrientation::Positive);
    if (params.orientation != OrientationMode::Positive) runs.push_back(DetailOrientation::Negative);

    TexelParams tp;
    tp.radius = seg.radius;
    tp.merge_overlap = params.merge_overlap;
    tp.min_depth_rel = params.min_depth_rel;
    tp.min_faces = params.min_faces;
    auto index_of = [](DetailOrientation o) { return o == DetailOrientation::Positive ? 0 : 1; };

    // Depth maps and texels of the orientations in `which`, each from surface(o); two at a
    // time in parallel (each CGAL tree is built by one thread).
    std::optional<DepthMap> depth_of[2];
    std::optional<TexelSet> set_of[2];
    auto depth_and_texels = [&](const std::vector<DetailOrientation>& which, const std::string& suffix,
                                auto&& surface) {
        auto depth = [&](DetailOrientation o) {
            set_of[index_of(o)].reset();  // a second pass: the first one's go first
            depth_of[index_of(o)].reset();
            depth_of[index_of(o)] = make_depth_map(mesh, seg.metrics.vertex_normal, surface(o), o);
        };
        auto texels = [&](DetailOrientation o) {
            set_of[index_of(o)] = make_texels(mesh, seg.topology, *depth_of[index_of(o)], tp);
        };
        if (which.size() == 1) {
            const std::string name = std::string(orientation_name(which[0])) + suffix;
            timed(observer, "depth map (" + name + ")", [&] { depth(which[0]); });
            timed(observer, "texels (" + name + ")", [&] { texels(which[0]); });
        } else if (which.size() == 2) {
            timed(observer, "depth maps (positive, negative" + suffix + ")",
                  [&] { detail::parallel_invoke([&] { depth(which[0]); }, [&] { depth(which[1]); }); });
            timed(observer, "texels (positive, negative" + suffix + ")",
                  [&] { detail::parallel_invoke([&] { texels(which[0]); }, [&] { texels(which[1]); }); });
        }
    };
    auto first_surface = [&](DetailOrientation) -> const SmoothedSurface& { return smoothed; };
    if (!params.remove_rims) smoother.reset();  // its disc records are not needed again
    depth_and_texels(runs, "", first_surface);

    // Rim removal (docs/rims.md): the details of the other orientation are left out of a
    // second smoothing, so that they no longer drag the smoothed surface and raise rims.
    // Only where a rim can be: with one orientation asked, the other is computed only when
    // one of its texels may be deeper than one of ours.
    bool rims_wanted = false;
    if (params.remove_rims) {
        for (DetailOrientation o : runs)
            rims_wanted = rims_wanted || rims_possible(mesh, seg.metrics.vertex_normal, smoothed,
                                                       *set_of[index_of(o)], *depth_of[index_of(o)]);
        if (rims_wanted && runs.size() == 1) {
            const DetailOrientation other =
                runs[0] == DetailOrientation::Positive ? DetailOrientation::Negative : DetailOrientation::Positive;
            depth_and_texels({other}, "", first_surface);
        }
    }
    std::optional<SmoothedSurface> second[2];
    seg.run_excluded_texels.assign(runs.size(), 0);
    if (rims_wanted) {
        const Rims rims = timed(observer, "rims", [&] {
            RimParams rp;
            rp.radius = seg.radius;
            return make_rims(mesh, seg.topology, *set_of[0], *depth_of[0], *set_of[1], *depth_of[1], rp);
        });
        for (std::size_t r = 0; r < runs.size(); ++r) {
            const bool positive = runs[r] == DetailOrientation::Positive;
            const std::vector<char>& excluded = positive ? rims.exclude_for_positive : rims.exclude_for_negative;
            if (excluded.empty()) continue;
            seg.run_excluded_texels[r] = positive ? rims.num_excluded_for_positive : rims.num_excluded_for_negative;
            second[index_of(runs[r])] =
                timed(observer, "smoothing (" + std::string(orientation_name(runs[r])) + ", without rims)",
                      [&] { return smoother->smooth(excluded); });
        }
        if (runs.size() == 1) {  // the other orientation was only needed to find the rims
            const int other = 1 - index_of(runs[0]);
            depth_of[other].reset();
            set_of[other].reset();
        }
    }
    smoother.reset();
    std::vector<DetailOrientation> again;  // the runs smoothed a second time
    for (DetailOrientation o : runs)
        if (second[index_of(o)]) again.push_back(o);
    depth_and_texels(again, ", without rims",
                     [&](DetailOrientation o) -> const SmoothedSurface& { return *second[index_of(o)]; });
    for (auto& s2 : second) s2.reset();

    seg.face_texel.assign(mesh.num_faces(), -1);
    std::vector<std::pair<int, int>> run_texel_range;  // [first, last) texel ids of each run
    for (DetailOrientation o : runs) {
        const std::string name = orientation_name(o);
        const int k = index_of(o);
        DepthMap depth = std::move(*depth_of[k]);
        TexelSet set = std::move(*set_of[k]);
        depth_of[k].reset();
        set_of[k].reset();
        // A face already in a texel of the first orientation stays there.
        const int first = static_cast<int>(seg.texels.size());
        int num_dropped = 0;
        for (auto& t : set.texels) {
            std::vector<int> kept;
            for (int f : t.faces)
                if (seg.face_texel[f] < 0) kept.push_back(f);
            if (static_cast<int>(kept.size()) < params.min_faces) {
                ++num_dropped;
                continue;
            }
            t.faces = std::move(kept);
            const int id = static_cast<int>(seg.texels.size());
            for (int f : t.faces) seg.face_texel[f] = id;
            seg.texels.push_back(std::move(t));
        }
        if (num_dropped > 0)
            seg.diagnostics.push_back({"segmentation", std::to_string(num_dropped) + " " + name +
                                                           " texels lay inside texels of the other orientation"});
        for (const auto& d : set.diagnostics) seg.diagnostics.push_back(d);
        set.texels.clear();
        seg.texel_sets.push_back(std::move(set));
        run_texel_range.emplace_back(first, static_cast<int>(seg.texels.size()));
        (o == DetailOrientation::Positive ? seg.positive_depth : seg.negative_depth) = std::move(depth);
    }

    seg.curvature = timed(observer, "curvature", [&] {
        CurvatureParams cp;
        cp.radius = params.curvature_scale * seg.radius;
        cp.only.assign(static_cast<std::size_t>(mesh.num_vertices()), 0);  // texel vertices
        for (int f = 0; f < mesh.num_faces(); ++f)
            if (seg.face_texel[f] >= 0)
                for (int v : mesh.faces[f]) cp.only[v] = 1;
        return make_curvature(mesh, seg.topology, seg.metrics.vertex_normal, cp);
    });
    seg.features = timed(observer, "features", [&] {
        FeatureInputs in;
        in.mesh = &mesh;
        in.topology = &seg.topology;
        in.curvature = &seg.curvature;
        in.positive_depth = seg.positive_depth ? &*seg.positive_depth : nullptr;
        in.negative_depth = seg.negative_depth ? &*seg.negative_depth : nullptr;
        in.largest_side = seg.metrics.largest_side;
        return make_feature_table(in, seg.texels);
    });
    for (const auto& d : seg.features.diagnostics) seg.diagnostics.push_back(d);

    timed(observer, "clustering", [&] {
        seg.texel_texture.assign(seg.texels.size(), -1);
        for (std::size_t r = 0; r < runs.size(); ++r) {
            const auto [first, last] = run_texel_range[r];
            ClusteringResult c = make_clustering(
                seg.features.values.block(first, 0, last - first, kNumClusteringFeatures), params.clustering);
            for (int i = first; i < last; ++i) seg.texel_texture[i] = seg.num_textures + c.labels[i - first];
            for (int k = 0; k < c.num_clusters; ++k) seg.texture_orientation.push_back(runs[r]);
            seg.num_textures += c.num_clusters;
            for (const auto& d : c.diagnostics) seg.diagnostics.push_back(d);
            seg.clusterings.push_back(std::move(c));
        }
        seg.face_texture.assign(mesh.num_faces(), -1);
        for (int f = 0; f < mesh.num_faces(); ++f)
            if (seg.face_texel[f] >= 0) seg.face_texture[f] = seg.texel_texture[seg.face_texel[f]];
    });
    return seg;
}

}  // namespace

}  // namespace geotex
