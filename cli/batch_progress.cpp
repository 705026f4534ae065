// What the user of geotex batch sees (batch_progress.hpp).

#include "cli/batch_progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "cli/output.hpp"
#include "common/detail/csv.hpp"
#include "common/detail/text.hpp"

namespace geotex::cli {

std::string duration_text(double s) {
    char buf[32];
    if (s < 10)
        std::snprintf(buf, sizeof buf, "%.1fs", s);
    else if (s < 60)
        std::snprintf(buf, sizeof buf, "%.0fs", s);
    else if (s < 3600)
        std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s) / 60,
                      static_cast<int>(s) % 60);
    else
        std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s) / 3600,
                      static_cast<int>(s) % 3600 / 60);
    return buf;
}

BatchProgress::BatchProgress(bool quiet, std::size_t total)
    : quiet_(quiet), tty_(::isatty(STDERR_FILENO) != 0), total_(total) {}

void BatchProgress::finished(const Job& job, std::size_t done, std::size_t failed) {
    if (job.status == Status::Failed) {
        clear();
        // The reason names the file or the manifest row; the id leads when it helps.
        const bool id_in_reason = job.reason.find(job.object->id) != std::string::npos;
        warn((id_in_reason || job.object->id.empty() ? ""
                                                     : detail::printable(job.object->id) + ": ") +
             job.reason);
    } else if (!quiet_ && !tty_) {
        std::fprintf(stderr, "geotex: [%zu/%zu] %s %s %.2f s (%ld texels, %ld textures)\n", done,
                     total_, job.object->id.c_str(), status_name(job.status), job.seconds,
                     job.texels, job.textures);
    }
    done_ = done;
    failed_ = failed;
    if (job.status == Status::Ok) {
        ++ran_;
        run_seconds_ += job.seconds;
    }
    draw(0, true);
}

void BatchProgress::draw(std::size_t running, bool force) {
    if (quiet_ || !tty_) return;
    const auto now = Clock::now();
    if (!force && now - last_draw_ < std::chrono::milliseconds(200)) return;
    last_draw_ = now;
    const int width = 30;
    const int filled = total_ ? static_cast<int>(width * done_ / total_) : width;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::string eta = "--";
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (done_ > skipped_at_start_ && done_ < total_)
        eta = duration_text(elapsed / static_cast<double>(done_ - skipped_at_start_) *
                            static_cast<double>(total_ - done_));
    std::fprintf(stderr, "\rgeotex: batch [%s] %zu/%zu  %zu failed  %zu running  ETA %s   ",
                 bar.c_str(), done_, total_, failed_, running, eta.c_str());
    drawn_ = true;
}

void BatchProgress::clear() {
    if (drawn_) std::fprintf(stderr, "\r%*s\r", 100, "");
    drawn_ = false;
}

void BatchProgress::skipped_before_start(std::size_t n) {
    skipped_at_start_ = n;
    done_ = n;
    start_ = Clock::now();
}

void write_summary(const std::string& path, const std::vector<Job>& jobs) {
    OutputSet set(OutputLinks::Refuse);
    set.add(path, [&](std::ostream& out) {
        out << "id,mesh,status,seconds,texels,textures,reason\n";
        for (const Job& j : jobs) {
            char seconds[32];
            std::snprintf(seconds, sizeof seconds, "%.3f", j.seconds);
            out << detail::csv_field(j.object->id) << ',' << detail::csv_field(j.object->mesh)
                << ',' << status_name(j.status) << ',' << seconds << ','
                << (j.texels >= 0 ? std::to_string(j.texels) : "") << ','
                << (j.textures >= 0 ? std::to_string(j.textures) : "") << ','
                << detail::csv_field(j.reason) << '\n';
        }
    });
    set.commit();
}

void print_totals(const BatchOptions& o, const BatchPlan& plan, const std::vector<Job>& jobs,
                  double seconds) {
    std::size_t ok = 0, skipped = 0, failed = 0, not_run = 0;
    for (const Job& j : jobs) {
        ok += j.status == Status::Ok;
        skipped += j.status == Status::Skipped;
        failed += j.status == Status::Failed;
        not_run += j.status == Status::NotRun;
    }
    std::printf("%s: %zu annotated, %zu up to date, %zu failed%s in %.1f s; summary in %s\n",
                o.input.c_str(), ok, skipped, failed,
                not_run ? (", " + std::to_string(not_run) + " not run").c_str() : "", seconds,
                plan.summary_path.c_str());
}

}  // namespace geotex::cli
