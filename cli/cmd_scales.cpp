// geotex scales: the texels of a mesh over a series of scales, and the scales where they are
// stable (issue 20, docs/scales.md).

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/segment_run.hpp"
#include "geometry/scale_series.hpp"
#include "pipeline/scale_report.hpp"

namespace geotex::cli {

namespace {

struct ScalesOptions {
    CommonOptions common;
    SegmentRunOptions run;
    ScaleSeriesParams series;
    std::string json;
    std::string plot;
};

void print_series(const std::string& mesh, const ScaleSeries& series, int faces) {
    std::printf("%s: %d scales from %s to %s of the largest side (%d faces)\n", mesh.c_str(),
                static_cast<int>(series.steps.size()),
                scale_percent(series.steps.front().radius_rel).c_str(),
                scale_percent(series.steps.back().radius_rel).c_str(), faces);
    std::printf("%8s %12s %7s %8s %10s %9s\n", "scale", "radius", "texels", "textures",
                "persistent", "stability");
    for (const ScaleStep& s : series.steps) {
        if (s.skipped) {
            std::printf("%8s %12.6g %7s\n", scale_percent(s.radius_rel).c_str(), s.radius,
                        "skipped");
            continue;
        }
        std::printf("%8s %12.6g %7d %8d %10d %9.2f%s\n", scale_percent(s.radius_rel).c_str(),
                    s.radius, s.texels, s.textures, s.persistent, s.stability,
                    s.stable ? "  stable" : "");
    }
    if (series.best < 0) {
        std::printf("no stable scale\n");
        return;
    }
    for (const ScalePlateau& p : series.plateaus)
        std::printf("plateau %s to %s: recommended %s (%d persistent texels)\n",
                    scale_percent(series.steps[p.first].radius_rel).c_str(),
                    scale_percent(series.steps[p.last].radius_rel).c_str(),
                    scale_percent(series.steps[p.recommended].radius_rel).c_str(),
                    series.steps[p.recommended].persistent);
    std::printf("best: --scale %.4g\n", series.steps[series.best].radius_rel);
    // Details at several scales (letters on bosses, strokes on bumps): say how to keep them all.
    if (series.plateaus.size() > 1) {
        std::string list;
        for (const ScalePlateau& p : series.plateaus)
            list +=
                (list.empty() ? "" : ", ") + scale_percent(series.steps[p.recommended].radius_rel);
        std::printf(
            "levels: %s (--scale auto --levels segments every plateau of the default "
            "series, docs/scales.md)\n",
            list.c_str());
    }
}

int run_scales(ScalesOptions& o) {
    apply_segmentation_flags(o.run);
    if (!(o.series.min_rel > 0 && o.series.min_rel < o.series.max_rel && o.series.max_rel < 1))
        throw CliError(kExitUsage, "--from " + scale_percent(o.series.min_rel) + " and --to " +
                                       scale_percent(o.series.max_rel) +
                                       ": need 0 < --from < --to < 1 (fractions of the largest "
                                       "side)");
    try {
        scale_series_radii(o.series);  // checks the series' parameters before any reading
    } catch (const Error& e) {
        throw CliError(kExitUsage, e.what());
    }
    check_output_paths({{"--json", o.json}, {"--plot", o.plot}}, {{"MESH", o.run.mesh}});
    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    const InputMesh input = load_mesh(o.run.mesh, progress);
    progress.end_work_lines();  // the series may segment two scales at once
    // Each scale's line says how long the rest should take: the mean time of the scales done
    // so far times the scales left (the skipped ones are the finest, so every scale after the
    // first computed one is computed too).
    const auto start = std::chrono::steady_clock::now();
    int done = 0;
    auto report = [&](int index, int count, double rel) {
        std::string line = "scale " + std::to_string(index + 1) + "/" + std::to_string(count) +
                           ": " + scale_percent(rel);
        if (done > 0) {
            const double elapsed =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            char eta[64];
            std::snprintf(eta, sizeof eta, " (%.1f s so far, about %.0f s left)", elapsed,
                          elapsed / done * (count - index));
            line += eta;
        }
        ++done;
        progress.note(line);
    };
    const ScaleSeries series = in_phase(kExitProcessing, o.run.mesh, [&] {
        return run_scale_series(input.repaired.mesh, o.run.params, o.series, report);
    });
    for (const std::string& note : series.notes) progress.note(o.run.mesh + ": " + note);
    OutputSet outputs;
    if (!o.json.empty())
        outputs.add(o.json, [&](std::ostream& out) {
            nlohmann::ordered_json j = scale_series_json(series, o.series);
            j["mesh"] = o.run.mesh;
            j["orientation"] = name_of(o.run.params.orientation);
            out << j.dump(2) << '\n';
        });
    if (!o.plot.empty())
        outputs.add(o.plot, [&](std::ostream& out) {
            out << scale_series_svg(series, o.series, o.run.mesh);
        });
    outputs.commit();
    print_series(o.run.mesh, series, static_cast<int>(input.repaired.mesh.faces.size()));
    return 0;
}

}  // namespace

Runner add_scales(CLI::App& sub) {
    auto o = std::make_shared<ScalesOptions>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "Segment MESH over a geometric series of scales r and tell which are stable: per scale "
        "the\n"
        "texels and textures found, how many texels persist into the neighbouring scales (the "
        "same\n"
        "faces, intersection over union above --match), and the stability (the fraction that\n"
        "persists). Runs of two or more stable scales are plateaus; each recommends, of its\n"
        "scales with nearly its most persistent texels (--near-most), the one with the fewest\n"
        "texels that do not persist (the finest on a tie), and that of the plateau with the most\n"
        "is printed as the --scale to use. The rule and its reasoning: docs/scales.md.");
    add_segmentation_options(sub, o->run, true, false);
    sub.add_option("--from", o->series.min_rel,
                   "Smallest scale, a fraction of the largest bounding-box side")
        ->check(CLI::Range(0.0, 1.0));
    sub.add_option("--to", o->series.max_rel, "Largest scale, a fraction of the largest side")
        ->check(CLI::Range(0.0, 1.0));
    sub.add_option("--steps", o->series.steps, "Number of scales, geometric from --from to --to")
        ->check(CLI::Range(2, 64));
    sub.add_option("--match", o->series.match_iou,
                   "Two texels of neighbouring scales are one detail when their faces' "
                   "intersection exceeds this fraction of their union")
        ->check(CLI::Range(0.5, 0.99));
    sub.add_option("--stable", o->series.stable_fraction,
                   "A scale is stable when this fraction of its texels persists")
        ->check(CLI::Range(0.01, 1.0));
    sub.add_option("--near-most", o->series.near_most,
                   "A plateau recommends, of its scales with at least this fraction of the "
                   "plateau's most persistent texels, the one with the fewest texels that do not "
                   "persist (the finest on a tie)")
        ->check(CLI::Range(0.01, 1.0));
    sub.add_option("--json", o->json, "Write the series as JSON");
    sub.add_option("--plot", o->plot,
                   "Write an SVG plot of texels, persistent texels and stability against r");
    add_output_options(sub);
    add_common_options(sub, o->common);
    return [o] { return run_scales(*o); };
}

}  // namespace geotex::cli
