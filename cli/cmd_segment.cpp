// geotex segment: texels and textures of one mesh (paper §3).

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/segment_run.hpp"
#include "cli/tile_jobs.hpp"
#include "pipeline/report_json.hpp"

namespace geotex::cli {

namespace {

struct SegmentOptions {
    CommonOptions common;
    SegmentRunOptions run;
    std::string output;
    std::string json;
    bool ascii = false;
    TileJobOptions job;
    const CLI::Option* output_option = nullptr;  ///< given (perhaps empty), or not
    const CLI::Option* json_option = nullptr;
    const CLI::Option* tile_dir_option = nullptr;
    const CLI::Option* pass_option = nullptr;
    const CLI::Option* shard_option = nullptr;
};

// --pass: one pass of a tiled run's jobs (tile_jobs.hpp); the parts are its only output.
int run_segment_pass(SegmentOptions& o) {
    if (o.output_option->count() > 0 || o.json_option->count() > 0)
        throw CliError(kExitUsage,
                       "--pass writes only the tiles' parts into --tile-dir; give --output and "
                       "--json to the run without --pass that joins them");
    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    run_tile_pass(o.run, o.job, progress);
    return 0;
}

int run_segment(SegmentOptions& o) {
    check_segmentation_options(o.run);
    o.run.tile_dir = o.job.dir;
    o.job.dir_given = o.tile_dir_option->count() > 0;
    o.job.pass_given = o.pass_option->count() > 0;
    o.job.shard_given = o.shard_option->count() > 0;
    check_tile_job_options(o.job, o.run.tiles);
    if (!o.job.pass.empty()) return run_segment_pass(o);
    if (o.output_option->count() == 0)
        throw CliError(kExitUsage, "--output is required (all but --pass write it)");
    check_output_paths({{"--output", o.output, true}, {"--json", o.json}}, {{"MESH", o.run.mesh}});
    auto threads = limit_threads(o.common.threads);
    Progress progress(o.common.quiet);
    const SegmentRun run = run_segmentation_stage(o.run, progress);
    const Segmentation& seg = run.seg;
    OutputSet outputs;
    timed_stage(progress, "writing", [&] {
        PlyWriteOptions w;
        w.binary = !o.ascii;
        w.comments = {"geotex segmentation of " + o.run.mesh,
                      "face texel: texel id, -1 = background",
                      "face texture: texture id, -1 = background; red green blue: texture colour"};
        // --levels: one more face property per level, "level_K_texel" (K = 0 the finest), so
        // that each level's texels can be seen apart; the main level's is also 'texel'.
        std::vector<FaceAttribute> levels;
        for (std::size_t k = 0; k < run.levels.size(); ++k) {
            levels.push_back({"level_" + std::to_string(k) + "_texel", PlyScalarType::Int32,
                              &level_segmentation(run.levels, k, seg).face_texel});
            w.comments.push_back("face level_" + std::to_string(k) + "_texel: texel id at scale " +
                                 scale_percent(run.levels[k].radius_rel) + ", -1 = background" +
                                 (run.levels[k].main ? " (the main level)" : ""));
        }
        outputs.add(o.output,
                    [&](std::ostream& out) { write_segmentation_ply(out, run, levels, w); });
        if (!o.json.empty()) {
            const ReportInput input{o.run.mesh, run.input.format, run.input.repaired.report};
            outputs.add(o.json, [&](std::ostream& out) {
                out << report_text(segmentation_report(
                    seg, o.run.params, input, run.scale_choice ? &*run.scale_choice : nullptr,
                    &run.levels));
            });
        }
        outputs.commit();
    });
    print_texture_summary(o.run.mesh, seg, o.run.params.orientation);
    return 0;
}

}  // namespace

Runner add_segment(CLI::App& sub) {
    auto o = std::make_shared<SegmentOptions>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "Find the salient details (3D texels) of MESH at the scale r and group them into geometric "
        "textures\n"
        "(paper section 3): oriented depth map over geodesic discs of radius r, seeds at local "
        "maxima, local\n"
        "Otsu regions, 18 features per texel, self-tuning spectral clustering. Writes the mesh as "
        "PLY with\n"
        "per-face int 'texel' and 'texture' (-1 = background) and uchar red/green/blue (one colour "
        "per\n"
        "texture, grey background), which MeshLab shows directly; --json adds a full report.");
    add_segmentation_options(sub, o->run);
    o->output_option = sub.add_option("-o,--output", o->output,
                                      "Segmentation PLY to write (required but with --pass)");
    sub.add_option("--tiles", o->run.tiles,
                   "Segment the mesh in this many spatial tiles, one at a time, each with a halo "
                   "of 6r around its box (docs/tiles.md): the same segmentation, byte for byte, "
                   "holding one tile's working data at a time, which saves memory where r is "
                   "small beside the object (1% or less), in 2 to 9 times the time; 0: the "
                   "whole mesh at once. Not with --scale auto")
        ->check(CLI::Range(0, 10000));
    o->tile_dir_option =
        sub.add_option("--tile-dir", o->job.dir,
                       "With --tiles: run the tiles as separate jobs (docs/tiles.md). With --pass, "
                       "write that pass's part of each tile into DIR; without, join every pass's "
                       "parts from DIR into the outputs (refusing a missing tile or another run's)")
            ->type_name("DIR");
    o->pass_option =
        sub.add_option("--pass", o->job.pass,
                       "With --tile-dir: run only this pass, after the parts of the passes before "
                       "it are in DIR: depth, texels, rims, depth-without-rims, "
                       "texels-without-rims, features (a pass the run does not need does "
                       "nothing). 'mesh', one job before the others, reads and repairs the mesh "
                       "once into DIR/mesh.part, which every later job then reads instead, and "
                       "cuts it into DIR/mesh/tile-K.part, from which the jobs of every pass "
                       "read their tile alone")
            ->type_name("NAME");
    sub.add_option("--tile", o->job.tile, "With --pass: only tile K (1 to N)")
        ->type_name("K")
        ->check(CLI::Range(1, 10000))
        ->default_str("all");
    o->shard_option =
        sub.add_option(
               "--shard", o->job.shard,
               "With --pass: only the tiles K with (K - 1) mod M = i - 1, for a Slurm array "
               "or GNU parallel (examples/cluster/tiles-slurm.sh)")
            ->type_name("i/M");
    o->json_option =
        sub.add_option("--json", o->json,
                       "Also write a JSON report: per texel its faces, 18 features and texture");
    sub.add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
    add_output_options(sub);
    add_common_options(sub, o->common);
    return [o] { return run_segment(*o); };
}

}  // namespace geotex::cli
