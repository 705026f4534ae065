#pragma once
// The children of geotex batch: at most --jobs running, each timed out after --timeout
// (SIGTERM, then SIGKILL 5 s later), each stamped when it ends well. Internal to cli/.

#include <cstddef>
#include <vector>

#include "annotation/dictionary.hpp"
#include "cli/batch_job.hpp"
#include "cli/batch_progress.hpp"

namespace geotex::cli {

/// Runs the jobs of `queue` (indices into `jobs`), a child process each, until all have
/// ended, or a stop signal came (g_batch_stop_signal) and every child has ended; the jobs a
/// stop left are NotRun. `done` and `failed` count the jobs that ended before. Returns the
/// number of failed jobs, those before included.
std::size_t run_children(const BatchOptions& o, const BatchPlan& plan, const Dictionary& dictionary,
                         std::vector<Job>& jobs, BatchProgress& progress,
                         const std::vector<std::size_t>& queue, std::size_t done,
                         std::size_t failed);

}  // namespace geotex::cli
