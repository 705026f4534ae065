// geotex batch: a whole collection annotated into one output directory (docs/collections.md).
// Each object runs in a child process, forked to run what `geotex annotate` runs
// (annotate_object): a mesh that crashes or exhausts memory takes only itself down, memory
// stays flat however large the collection, a timeout can kill it, and --jobs children use
// the cores. The parent plans (batch_plan: options, shard, what is up to date), schedules
// the children (batch_scheduler: stamps each finished object), and reports (batch_progress:
// the bar, summary.csv, the totals).

#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <memory>

#include "cli/batch_job.hpp"
#include "cli/batch_plan.hpp"
#include "cli/batch_progress.hpp"
#include "cli/batch_scheduler.hpp"
#include "cli/description_options.hpp"
#include "cli/dictionary_input.hpp"

namespace geotex::cli {

std::atomic<int> g_batch_stop_signal{0};

namespace {

using Clock = std::chrono::steady_clock;

extern "C" void batch_stop(int sig) { g_batch_stop_signal = sig; }

int run_batch(BatchOptions& o) {
    const BatchPlan plan = check_batch_options(o);
    const Dictionary dictionary = load_dictionary(o.dictionary);
    const Collection collection = read_collection(o.input);
    if (collection.objects.empty())
        throw CliError(kExitInput,
                       o.input + ": no meshes (.ply, .off, .obj, .stl) in this collection");
    make_directory(plan.out_dir / "objects");
    make_directory(plan.out_dir / "logs");
    const InputFiles inputs = batch_inputs(o, collection);
    check_output_paths({{"--output", plan.summary_path, true, true}},
                       inputs);  // fail now, not after hours

    Progress notes(o.common.quiet);
    for (const auto& n : collection.notes) notes.note(n);
    std::vector<Job> jobs = shard_jobs(collection, plan);
    notes.note("batch: " + std::to_string(jobs.size()) + " of " +
               std::to_string(collection.objects.size()) + " objects" +
               (plan.num_shards > 1 ? " in shard " + o.shard : std::string()) + " -> " + o.output);

    // From here a stop (SIGINT, SIGTERM, SIGHUP) ends the batch with a summary of what was
    // done, the rest marked interrupted.
    std::signal(SIGINT, batch_stop);
    std::signal(SIGTERM, batch_stop);
    std::signal(SIGHUP, batch_stop);

    // Up-to-date objects are skipped, and what cannot run fails, before anything runs.
    std::vector<std::size_t> queue;
    std::size_t failed = 0;
    for (std::size_t i = 0; i < jobs.size() && g_batch_stop_signal == 0; ++i) {
        if (!prepare_job(o, plan, dictionary, inputs, jobs[i])) break;
        if (jobs[i].status == Status::Failed) ++failed;
        if (jobs[i].status == Status::NotRun) queue.push_back(i);
    }
    const std::size_t done = jobs.size() - queue.size();
    BatchProgress progress(o.common.quiet, jobs.size());
    progress.skipped_before_start(done);
    if (done > 0)
        notes.note("batch: " + std::to_string(done - failed) + " up to date, " +
                   std::to_string(failed) + " failed before running, " +
                   std::to_string(queue.size()) + " to run (" + std::to_string(plan.job_slots) +
                   " at a time, " + std::to_string(plan.threads) + " thread" +
                   (plan.threads > 1 ? "s" : "") + " each)");
    for (const Job& job : jobs)
        if (job.status == Status::Failed) progress.finished(job, done, failed);

    const auto batch_start = Clock::now();
    failed = run_children(o, plan, dictionary, jobs, progress, queue, done, failed);
    progress.clear();
    if (g_batch_stop_signal != 0)
        for (Job& j : jobs)
            if (j.status == Status::NotRun && j.reason.empty()) j.reason = "interrupted";
    write_summary(plan.summary_path, jobs);
    print_totals(o, plan, jobs, std::chrono::duration<double>(Clock::now() - batch_start).count());
    if (g_batch_stop_signal != 0) {
        const int sig = g_batch_stop_signal;
        std::signal(sig, SIG_DFL);
        std::raise(sig);
    }
    return failed > 0 ? kExitProcessing : 0;
}

}  // namespace

Runner add_batch(CLI::App& sub) {
    auto o = std::make_shared<BatchOptions>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "Annotate a whole collection: every mesh of DIR (.ply, .off, .obj, .stl), or of a CSV "
        "manifest (columns mesh\n"
        "and optionally id, object, mesh_unit), as 'geotex annotate' does, into "
        "OUTDIR/objects/<id>/ (RDF, JSON-LD, JSON report,\n"
        "segmentation PLY, geometry cache) with a stamp run.json written last. A rerun skips the "
        "objects whose mesh, dictionary\n"
        "and options are unchanged; a changed dictionary re-runs only the annotation (the geometry "
        "is cached). One\n"
        "bad mesh never stops the batch: OUTDIR/summary.csv lists every object with its status, "
        "time, counts and the\n"
        "reason of each failure. --shard i/N splits the collection by object id for a cluster (no "
        "coordinator):\n"
        "see docs/collections.md and examples/cluster/. Exit code 3 when any object failed.");
    sub.add_option("input", o->input, "Directory of meshes, or a CSV manifest")->required();
    sub.add_option("-o,--output", o->output, "Output directory (created when missing)")->required();
    sub.add_option("--jobs", o->jobs, "Meshes processed at once (default: one per core)")
        ->check(CLI::Range(1, 256))
        ->default_str("cores");
    sub.add_option("--shard", o->shard,
                   "Process only shard i of N (1 <= i <= N), chosen by a hash of the object id")
        ->type_name("i/N");
    sub.add_option(
        "--base-template", o->base_template,
        "Base IRI of each object: {id} is the object id (percent-encoded), {sha256} the mesh "
        "digest, e.g. "
        "'https://example.org/object/{id}/' (default: RFC 6920 hash names, as 'geotex annotate')");
    sub.add_option(
        "--object-template", o->object_template,
        "IRI of the physical object each mesh is a scan of (crm:P138_represents), e.g. "
        "'https://museum.example.org/object/{id}'; a manifest's 'object' column takes precedence");
    sub.add_option("--creator", o->creator,
                   "IRI of the person or organisation responsible for the annotations")
        ->type_name("IRI");
    sub.add_option("--mesh-unit", o->mesh_unit,
                   "Unit of the mesh coordinates (mm, cm, m or in); a manifest's 'mesh_unit' "
                   "column takes precedence")
        ->type_name("UNIT");
    // No custom type name: FLOAT is what makes refuse_non_finite_numbers check it.
    sub.add_option("--timeout", o->timeout, "Give up on a mesh after this many seconds (0: never)");
    sub.add_flag("--force", o->force, "Run every object again, even those that are up to date");
    add_segmentation_options(sub, o->run, false);
    add_output_options(sub);  // --replace-read-only holds for every object's outputs too
    sub.add_option("--dictionary", o->dictionary,
                   "YAML interval dictionary (default: the built-in one)");
    sub.add_option("--lang", o->lang,
                   "Language of the texture labels (a language of the dictionary)");
    add_description_options(sub, o->description);
    add_common_options(sub, o->common);
    sub.get_option("--threads")
        ->description("Worker threads of each mesh")
        ->default_str("cores/jobs");
    return [o] { return run_batch(*o); };
}

}  // namespace geotex::cli
