#include "geometry/segmentation.hpp"

#include <chrono>
#include <optional>
#include <cmath>
#include <string>

#include "geometry/errors.hpp"
#include "geometry/rims.hpp"

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

Segmentation run_segmentation(const Mesh& mesh, const SegmentationParams& params, const StageObserver& observer) {
    if (mesh.num_faces() == 0) throw InvalidInput("segmentation: the mesh has no face");
    Segmentation seg;
    timed(observer, "topology", [&] {
        seg.topology = make_topology(mesh);
        seg.metrics = make_mesh_metrics(mesh, seg.topology);
    });
    seg.radius = resolve_radius(params, seg.metrics.largest_side);
    // A disc needs a few rings of vertices for its mean to mean anything: below about three
    // edge lengths the depth is dominated by the triangulation itself.
    if (seg.radius < 3 * seg.metrics.mean_edge_length)
        seg.diagnostics.push_back({"segmentation", "the radius (" + std::to_string(seg.radius) +
                                                       ") is less than three mean edge lengths (" +
                                                       std::to_string(seg.metrics.mean_edge_length) +
                                                       "): the discs hold too few vertices and the texels "
                                                       "follow the triangulation; use a larger scale or a finer mesh"});

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

    // First pass: the depth maps and texels of the smoothing above; the rim removal needs both
    // orientations whatever is asked.
    std::optional<DepthMap> first_depth[2];
    std::optional<TexelSet> first_set[2];
    const std::vector<DetailOrientation> first_runs =
        params.remove_rims ? std::vector<DetailOrientation>{DetailOrientation::Positive, DetailOrientation::Negative}
                           : runs;
    if (!params.remove_rims) smoother.reset();
    for (DetailOrientation o : first_runs) {
        const std::string name = orientation_name(o);
        first_depth[index_of(o)] = timed(observer, "depth map (" + name + ")",
                                         [&] { return make_depth_map(mesh, seg.metrics.vertex_normal, smoothed, o); });
        first_set[index_of(o)] = timed(observer, "texels (" + name + ")",
                                       [&] { return make_texels(mesh, seg.topology, *first_depth[index_of(o)], tp); });
    }

    // Rim removal (docs/rims.md): the details of the other orientation are left out of a
    // second smoothing, so that they no longer drag the smoothed surface and raise rims.
    std::optional<SmoothedSurface> second[2];
    seg.run_excluded_texels.assign(runs.size(), 0);
    if (params.remove_rims) {
        const Rims rims = timed(observer, "rims", [&] {
            RimParams rp;
            rp.radius = seg.radius;
            return make_rims(mesh, seg.topology, *first_set[0], *first_depth[0], *first_set[1], *first_depth[1], rp);
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
        smoother.reset();
    }

    seg.face_texel.assign(mesh.num_faces(), -1);
    std::vector<std::pair<int, int>> run_texel_range;  // [first, last) texel ids of each run
    for (DetailOrientation o : runs) {
        const std::string name = orientation_name(o);
        const int k = index_of(o);
        DepthMap depth;
        TexelSet set;
        if (second[k]) {
            depth = timed(observer, "depth map (" + name + ", without rims)",
                          [&] { return make_depth_map(mesh, seg.metrics.vertex_normal, *second[k], o); });
            second[k].reset();
            set = timed(observer, "texels (" + name + ", without rims)", [&] { return make_texels(mesh, seg.topology, depth, tp); });
        } else {
            depth = std::move(*first_depth[k]);
            set = std::move(*first_set[k]);
        }
        first_depth[k].reset();
        first_set[k].reset();
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
            ClusteringResult c = make_clustering(seg.features.values.middleRows(first, last - first), params.clustering);
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

}  // namespace geotex
