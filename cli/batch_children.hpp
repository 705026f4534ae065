#pragma once
// The child processes of geotex batch: one per object, forked with its stderr in the
// object's log, and what is left to do when one ends badly.

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace geotex::cli {

/// A child that is running, for the scheduler.
struct RunningChild {
    std::size_t job = 0;
    std::chrono::steady_clock::time_point start;
    bool terminated = false;  ///< SIGTERM sent (timeout or stop)
    std::chrono::steady_clock::time_point terminated_at;
};

/// Forks a child that runs `work` (through run_command, so an error is the usual one line)
/// and exits with its code; its stdout goes nowhere, its stderr to `log` (never through a
/// link); SIGINT, SIGTERM and SIGHUP remove its temporary outputs and end it, and it dies
/// with the batch (PR_SET_PDEATHSIG). Returns the child's pid, or -1 (errno set).
///
/// A fork without exec: the child starts with the batch's parsed options and dictionary, so
/// nothing is rebuilt or read again. That is safe only from a process with one thread: the
/// batch's parent runs no parallel loop (TBB's workers would not exist in the child).
pid_t spawn_child(const std::function<int()>& work, const std::string& log);

/// The last "geotex: error: ..." line of a child's log, else how it ended.
std::string failure_reason(const std::string& log, int wait_status);

/// Removes the temporary files (".<name>.tmp.<pid>.<n>", cli/output.cpp) that the child `pid`
/// left in its object directory `dir` when it could not remove them itself: killed by SIGKILL
/// (its grace after SIGTERM ran out, on a loaded machine) or by a signal it does not catch.
void remove_child_temporaries(const std::filesystem::path& dir, pid_t pid);

}  // namespace geotex::cli
