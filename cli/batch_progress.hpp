#pragma once
// What the user of geotex batch sees: a bar with an ETA on a terminal (a line per object
// otherwise), summary.csv, and the last line with the totals. Internal to cli/.

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "cli/batch_job.hpp"

namespace geotex::cli {

/// "4.2s", "42s", "4m02s", "1h05m": a duration for people.
std::string duration_text(double seconds);

/// The batch's progress on stderr: each failure as a warning, and either a bar with the ETA
/// (a terminal) or one line per finished object.
class BatchProgress {
  public:
    BatchProgress(bool quiet, std::size_t total);

    /// `job` has ended; `done` and `failed` count every ended job so far.
    void finished(const Job& job, std::size_t done, std::size_t failed);

    /// The bar on a terminal: done/total, failures, running, ETA from the objects run so far.
    /// Redrawn at most every 200 ms unless `force`.
    void draw(std::size_t running, bool force = false);

    /// Clears the bar, so that a message can be printed.
    void clear();

    /// `n` jobs ended (up to date, or failed) before any ran: the ETA does not count them.
    void skipped_before_start(std::size_t n);

  private:
    using Clock = std::chrono::steady_clock;
    bool quiet_, tty_;
    std::size_t total_, done_ = 0, failed_ = 0, ran_ = 0, skipped_at_start_ = 0;
    double run_seconds_ = 0;
    bool drawn_ = false;
    Clock::time_point start_ = Clock::now(), last_draw_{};
};

/// Writes summary.csv (atomically, refusing a link): one row per job, in job order.
void write_summary(const std::string& path, const std::vector<Job>& jobs);

/// The last line on stdout: what was done, and where the summary is.
void print_totals(const BatchOptions& o, const BatchPlan& plan, const std::vector<Job>& jobs,
                  double seconds);

}  // namespace geotex::cli
