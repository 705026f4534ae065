#include "geometry/scale_series.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <unordered_map>
#include <utility>

#include "common/errors.hpp"
#include "geometry/detail/parallel.hpp"

namespace geotex {

namespace {

void check_params(const ScaleSeriesParams& p) {
    if (!(p.min_rel > 0 && p.min_rel < p.max_rel && p.max_rel < 1))
        throw InvalidInput("scale series: the scales must satisfy 0 < smallest < largest < 1");
    if (p.steps < 2) throw InvalidInput("scale series: at least 2 scales are needed");
    if (!(p.match_iou >= 0.5 && p.match_iou < 1))
        throw InvalidInput("scale series: the matching overlap must be in [0.5, 1)");
    if (!(p.stable_fraction > 0 && p.stable_fraction <= 1))
        throw InvalidInput("scale series: the stable fraction must be in (0, 1]");
    if (!(p.min_radius_edges >= 0 && std::isfinite(p.min_radius_edges)))
        throw InvalidInput("scale series: the least radius in edge lengths must be >= 0");
    if (!(p.near_most > 0 && p.near_most <= 1))
        throw InvalidInput("scale series: the near-most fraction must be in (0, 1]");
}

// The largest bounding-box side and the mean edge length, as make_mesh_metrics computes them,
// without the normals and areas a segmentation recomputes anyway.
std::pair<double, double> size_of(const Mesh& mesh) {
    if (mesh.faces.empty() || mesh.positions.empty())
        throw InvalidInput("scale series: the mesh has no faces");
    double total = 0;
    for (const auto& f : mesh.faces)
        for (int k = 0; k < 3; ++k)
            total += (mesh.positions[f[(k + 1) % 3]] - mesh.positions[f[k]]).norm();
    return {bounding_box(mesh.positions).sizes().maxCoeff(),
            total / (3.0 * static_cast<double>(mesh.faces.size()))};
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

}  // namespace

std::string scale_percent(double radius_rel) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g%%", 100 * radius_rel);
    return text;
}

std::vector<double> scale_series_radii(const ScaleSeriesParams& params) {
    check_params(params);
    std::vector<double> radii(params.steps);
    const double ratio = params.max_rel / params.min_rel;
    for (int k = 0; k < params.steps; ++k)
        radii[k] = params.min_rel * std::pow(ratio, static_cast<double>(k) / (params.steps - 1));
    radii.back() = params.max_rel;  // exactly, not pow's rounding of it
    return radii;
}

TexelOverlaps texel_overlaps(const std::vector<int>& face_texel_a, int na,
                             const std::vector<int>& face_texel_b, int nb) {
    if (face_texel_a.size() != face_texel_b.size())
        throw InvalidInput("texel overlaps: the labellings cover different face counts");
    TexelOverlaps out;
    out.size_a.assign(static_cast<std::size_t>(std::max(na, 0)), 0);
    out.size_b.assign(static_cast<std::size_t>(std::max(nb, 0)), 0);
    // Shared faces of each (texel of a, texel of b) pair that meet at all.
    std::unordered_map<long long, long> shared;
    for (std::size_t f = 0; f < face_texel_a.size(); ++f) {
        const int a = face_texel_a[f], b = face_texel_b[f];
        if (a >= na || b >= nb)
            throw InvalidInput("texel overlaps: a texel id is not below the texel count");
        if (a >= 0) ++out.size_a[static_cast<std::size_t>(a)];
        if (b >= 0) ++out.size_b[static_cast<std::size_t>(b)];
        if (a >= 0 && b >= 0) ++shared[static_cast<long long>(a) * nb + b];
    }
    out.pairs.reserve(shared.size());
    for (const auto& [pair, count] : shared)
        out.pairs.push_back({static_cast<int>(pair / nb), static_cast<int>(pair % nb), count});
    return out;
}

std::vector<bool> persisting_texels(const std::vector<int>& face_texel_a, int na,
                                    const std::vector<int>& face_texel_b, int nb, double min_iou) {
    const TexelOverlaps o = texel_overlaps(face_texel_a, na, face_texel_b, nb);
    std::vector<bool> persists(na, false);
    for (const TexelOverlaps::Pair& p : o.pairs) {
        const double iou = static_cast<double>(p.shared) /
                           static_cast<double>(o.size_a[p.a] + o.size_b[p.b] - p.shared);
        if (iou > min_iou) persists[p.a] = true;
    }
    return persists;
}

void choose_scales(ScaleSeries& series, const ScaleSeriesParams& params) {
    auto& steps = series.steps;
    std::vector<int> computed;
    for (int k = 0; k < static_cast<int>(steps.size()); ++k)
        if (!steps[k].skipped) computed.push_back(k);
    for (std::size_t i = 0; i < computed.size(); ++i) {
        ScaleStep& s = steps[computed[i]];
        const bool has_previous = i > 0, has_next = i + 1 < computed.size();
        // A texel persists when it is matched on each side that exists: both at the middle of
        // the series, the one neighbour at an end. A lone computed scale has none to compare.
        if (has_previous && has_next)
            s.persistent = std::min(s.persist_previous, s.persist_next);
        else if (has_previous)
            s.persistent = s.persist_previous;
        else if (has_next)
            s.persistent = s.persist_next;
        else
            s.persistent = 0;
        s.stability = s.texels > 0 ? static_cast<double>(s.persistent) / s.texels : 0;
        s.stable = s.texels > 0 && s.stability >= params.stable_fraction;
    }
    series.plateaus.clear();
    series.best = -1;
    int best_most = 0;  // the most persistent texels of the best plateau
    for (std::size_t i = 0; i < computed.size();) {
        if (!steps[computed[i]].stable) {
            ++i;
            continue;
        }
        ScalePlateau p;
        p.first = p.last = computed[i];
        const std::size_t start = i;
        int most = 0;
        for (; i < computed.size() && steps[computed[i]].stable; ++i) {
            p.last = computed[i];
            most = std::max(most, steps[computed[i]].persistent);
        }
        if (i - start < 2) continue;
        // Of the scales that keep nearly all the plateau's persistent texels, the one with
        // the fewest texels that do not persist (a detail split in two, a texel of noise or
        // of a rim: what a reader would not want), and the finest of those: a finer disc
        // follows a detail's border more closely, and a larger one starts to take the broad
        // relief of the surface (swellings, wear) for details.
        p.recommended = -1;
        for (std::size_t j = start; j < i; ++j) {
            const ScaleStep& s = steps[computed[j]];
            if (s.persistent < params.near_most * most) continue;
            if (p.recommended < 0 || s.texels - s.persistent < steps[p.recommended].texels -
                                                                   steps[p.recommended].persistent)
                p.recommended = computed[j];
        }
        series.plateaus.push_back(p);
        if (series.best < 0 || most > best_most) {
            series.best = p.recommended;
            best_most = most;
        }
    }
}

ScaleChoice choose_scale(ScaleSeries series, const ScaleSeriesParams& params) {
    ScaleChoice choice;
    choice.params = params;
    choice.stable = series.best >= 0;
    choice.chosen = series.best;
    if (choice.chosen < 0)
        for (int k = 0; k < static_cast<int>(series.steps.size()); ++k) {
            const ScaleStep& s = series.steps[k];
            if (!s.skipped &&
                (choice.chosen < 0 || s.persistent > series.steps[choice.chosen].persistent))
                choice.chosen = k;
        }
    if (choice.chosen < 0)
        throw InvalidInput("every scale of the series is below " + number(params.min_radius_edges) +
                           " mean edge lengths: the mesh is too coarse for scales from " +
                           scale_percent(params.min_rel) + " to " + scale_percent(params.max_rel));
    choice.series = std::move(series);
    return choice;
}

namespace {

// Meshes up to this many faces are segmented two scales at a time, so that the serial parts
// of one scale (the texels' region growing, the clustering, the loops between stages) overlap
// the parallel ones of the other. Above it, one at a time: a segmentation peaks at about 190
// bytes a face (bench/RESULTS.md, "Memory and time at scale"), and two of a mesh this large
// already hold about 0.8 GB.
constexpr int kMaxFacesTwoAtATime = 1 << 21;

// Runs fn so that a thread waiting inside it for its parallel loops only helps with them: it
// never takes up the other lane, which would run all that lane's scales nested inside this
// one and hold this scale's memory, and its result, until they are done.
template <class Fn>
void isolated(Fn&& fn) {
    if (detail::serial())
        fn();
    else
        tbb::this_task_arena::isolate(std::forward<Fn>(fn));
}

}  // namespace

ScaleSeries run_scale_series(const Mesh& mesh, const SegmentationParams& base,
                             const ScaleSeriesParams& params, const ScaleObserver& observer) {
    const std::vector<double> radii = scale_series_radii(params);
    const auto [largest_side, mean_edge] = size_of(mesh);
    const int count = static_cast<int>(radii.size());
    ScaleSeries series;
    series.steps.resize(radii.size());
    std::vector<int> computed;  // indices into series.steps, finest first
    for (int k = 0; k < count; ++k) {
        ScaleStep& step = series.steps[k];
        step.radius_rel = radii[k];
        step.radius = radii[k] * largest_side;
        step.skipped = step.radius < params.min_radius_edges * mean_edge;
        if (!step.skipped) computed.push_back(k);
    }
    const int n = static_cast<int>(computed.size());
    auto params_at = [&](int i) {
        SegmentationParams p = base;
        p.radius_rel = radii[computed[i]];
        p.radius = 0;
        return p;
    };
    if (n > 0) {
        // The parameters are checked before the topology is built, as run_segmentation does.
        check_segmentation_params(params_at(0));
        // The topology and metrics do not depend on r: built once for every scale.
        const SegmentationContext context(mesh);
        // The face labelling of each computed scale, kept until both its neighbours are done.
        std::vector<std::vector<int>> faces(n);
        std::vector<char> done(n, 0);
        int next = 0;
        // A scale that throws stops the lanes from taking new ones; its exception is rethrown
        // once the other lane has finished its scale (nothing is cancelled half-way), the
        // finest scale's when both throw, as one scale after the other would.
        std::exception_ptr error;
        int error_at = n;
        std::mutex mutex;
        // Persistence between the computed scales i and i + 1, once both are done.
        auto match = [&](int i) {
            ScaleStep& before = series.steps[computed[i]];
            ScaleStep& step = series.steps[computed[i + 1]];
            const auto back = persisting_texels(faces[i + 1], step.texels, faces[i], before.texels,
                                                params.match_iou);
            const auto forth = persisting_texels(faces[i], before.texels, faces[i + 1], step.texels,
                                                 params.match_iou);
            step.persist_previous = static_cast<int>(std::count(back.begin(), back.end(), true));
            before.persist_next = static_cast<int>(std::count(forth.begin(), forth.end(), true));
        };
        auto matched = [&](int i) {
            return (i == 0 || done[i - 1]) && (i + 1 == n || done[i + 1]);
        };
        // Each lane segments the next scale not yet taken until none is left; the results go
        // to their own step, and persistence is a function of two labellings, so the series
        // does not depend on which lane did what.
        auto lane = [&] {
            for (;;) {
                int i = -1;
                Segmentation seg;
                try {
                    {
                        const std::lock_guard<std::mutex> lock(mutex);
                        if (error || next == n) return;
                        i = next++;
                        if (observer) observer(computed[i], count, radii[computed[i]]);
                    }
                    isolated([&] { seg = context.run_without_topology(params_at(i)); });
                } catch (...) {
                    const std::lock_guard<std::mutex> lock(mutex);
                    if (i < error_at) {
                        error = std::current_exception();
                        error_at = i;
                    }
                    return;
                }
                const std::lock_guard<std::mutex> lock(mutex);
                ScaleStep& step = series.steps[computed[i]];
                step.texels = static_cast<int>(seg.texels.size());
                step.textures = seg.num_textures;
                faces[i] = std::move(seg.face_texel);
                done[i] = 1;
                if (i > 0 && done[i - 1]) match(i - 1);
                if (i + 1 < n && done[i + 1]) match(i);
                for (int j = std::max(0, i - 1); j <= std::min(n - 1, i + 1); ++j)
                    if (done[j] && matched(j)) std::vector<int>().swap(faces[j]);
            }
        };
        if (mesh.num_faces() <= kMaxFacesTwoAtATime)
            detail::parallel_invoke(lane, lane);
        else
            lane();
        if (error) std::rethrow_exception(error);
    }
    // The skipped scales are the finest ones: one note for all of them.
    int skipped = 0;
    while (skipped < static_cast<int>(radii.size()) && series.steps[skipped].skipped) ++skipped;
    if (skipped > 0)
        series.notes.push_back((skipped == 1 ? "scale " + scale_percent(radii[0])
                                             : "scales " + scale_percent(radii[0]) + " to " +
                                                   scale_percent(radii[skipped - 1])) +
                               " skipped: r is below " + number(params.min_radius_edges) +
                               " mean edge lengths (the discs would hold too few vertices)");
    choose_scales(series, params);
    return series;
}

}  // namespace geotex
