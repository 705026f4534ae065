#pragma once
// geotex batch before anything runs: the options checked, the objects of this shard, and for
// each object whether it is up to date, cannot run, or is to run (and then what its child
// runs). Internal to cli/.

#include <string>
#include <utility>
#include <vector>

#include "annotation/dictionary.hpp"
#include "cli/annotate_object.hpp"
#include "cli/batch_job.hpp"
#include "cli/output.hpp"

namespace geotex::cli {

/// Checks everything that needs no mesh, so a typo costs nothing. Throws CliError.
BatchPlan check_batch_options(BatchOptions& o);

/// Every input of the batch: no output may be one of them (a manifest row naming the
/// segmentation of another object, a summary over the manifest).
InputFiles batch_inputs(const BatchOptions& o, const Collection& collection);

/// "i/N" with 1 <= i <= N, as --shard takes it (batch, and the tiles of segment --pass).
/// Throws CliError kExitUsage naming --shard.
std::pair<int, int> parse_shard(const std::string& text);

/// The objects of this shard, in the collection's order. An object without a usable id is
/// reported by shard 1 only, so exactly once.
std::vector<Job> shard_jobs(const Collection& collection, const BatchPlan& plan);

/// Creates `dir` (and its parents) and checks that the batch can write in it; refuses a
/// link or a file at its name. Throws CliError (output).
void make_directory(const std::filesystem::path& dir);

/// Decides what `job` needs before anything runs: Failed (an unreadable mesh, an output
/// that may not be written), Skipped (its stamp matches: up to date) or still NotRun (to
/// run). Fills the digest, IRIs and unit of the job. Returns false when the batch is stopped
/// meanwhile.
bool prepare_job(const BatchOptions& o, const BatchPlan& plan, const Dictionary& dictionary,
                 const InputFiles& inputs, Job& job);

/// What makes the outputs of an object what they are, besides the mesh and dictionary bytes.
/// The dictionary's name is among them: the JSON report records it.
std::string options_digest(const BatchOptions& o, const Dictionary& dictionary, const Job& job);

/// What a child runs: `geotex annotate` of the object into its directory, with the batch's
/// options and dictionary. The outputs refuse links: one planted after prepare_job's check
/// is still not followed.
AnnotateJob annotate_job(const BatchOptions& o, const BatchPlan& plan, const Dictionary& dictionary,
                         const Job& job);

}  // namespace geotex::cli
