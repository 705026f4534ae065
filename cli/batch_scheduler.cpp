// The children of geotex batch (batch_scheduler.hpp).

#include "cli/batch_scheduler.hpp"

#include <sys/stat.h>
#include <sys/wait.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <map>
#include <memory>
#include <thread>

#include "cli/annotate_object.hpp"
#include "cli/batch_children.hpp"
#include "cli/batch_plan.hpp"
#include "cli/output.hpp"
#include "pipeline/batch_stamps.hpp"

namespace geotex::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Writes `dir`'s stamp (atomically, refusing a planted link) once the child's outputs are
/// all in place, and returns the counts it records.
StampCounts write_stamp(const fs::path& dir, const StampKey& key, const std::string& id,
                        const std::string& mesh, const std::string& graph_base) {
    const Stamp stamp =
        in_phase(kExitInput, "", [&] { return make_stamp(dir, key, id, mesh, graph_base); });
    OutputSet set(OutputLinks::Refuse);
    set.add((dir / kStampFile).string(), [&](std::ostream& out) { out << stamp.text; });
    set.commit();
    return stamp.counts;
}

/// The children of a batch: at most `job_slots` running, each timed out after --timeout
/// (SIGTERM, then SIGKILL 5 s later), each stamped when it ends well.
class Scheduler {
  public:
    Scheduler(const BatchOptions& o, const BatchPlan& plan, const Dictionary& dictionary,
              std::vector<Job>& jobs, BatchProgress& progress, std::size_t done, std::size_t failed)
        : o_(o),
          plan_(plan),
          dictionary_(dictionary),
          jobs_(jobs),
          progress_(progress),
          done_(done),
          failed_(failed) {}

    /// Runs the jobs of `queue` (indices into the jobs) until all have ended or a stop
    /// signal came and every child has ended. Returns the number of failed jobs.
    std::size_t run(const std::vector<std::size_t>& queue) {
        std::size_t next = 0;
        while ((next < queue.size() && g_batch_stop_signal == 0) || !running_.empty()) {
            while (g_batch_stop_signal == 0 && next < queue.size() &&
                   static_cast<int>(running_.size()) < plan_.job_slots)
                start(queue[next++]);
            if (g_batch_stop_signal != 0)
                for (auto& [pid, r] : running_) terminate(pid, r);
            int wait_status = 0;
            const pid_t pid = ::waitpid(-1, &wait_status, WNOHANG);
            if (pid > 0 && running_.count(pid) != 0) {
                finish(pid, wait_status);
                continue;
            }
            enforce_timeouts();
            progress_.draw(running_.size());
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return failed_;
    }

  private:
    void start(std::size_t i) {
        Job& job = jobs_[i];
        const fs::path dir = object_dir(plan_, job);
        std::error_code ec;
        fs::create_directory(dir, ec);  // objects/ exists: no parent is created
        struct stat st {};
        if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
            fail(job, dir.string() + ": cannot create the object's directory" +
                          (ec ? " (" + ec.message() + ")"
                              : std::string(" (something else is in its place)")));
            return;
        }
        fs::remove(dir / kStampFile, ec);  // incomplete until the new stamp is written
        auto annotate = std::make_shared<AnnotateJob>(annotate_job(o_, plan_, dictionary_, job));
        const pid_t pid =
            spawn_child([annotate] { return annotate_object(*annotate); }, log_path(plan_, job));
        if (pid < 0) {
            fail(job, std::string("cannot start a process (") + std::strerror(errno) + ")");
            return;
        }
        running_[pid] = {i, Clock::now(), false, {}};
    }

    void fail(Job& job, const std::string& reason) {
        job.status = Status::Failed;
        job.reason = reason;
        ended(job);
    }

    void ended(const Job& job) {
        ++done_;
        if (job.status == Status::Failed) ++failed_;
        progress_.finished(job, done_, failed_);
    }

    void terminate(pid_t pid, RunningChild& r) {
        if (r.terminated) return;
        ::kill(pid, SIGTERM);  // the child removes its temporaries
        r.terminated = true;
        r.terminated_at = Clock::now();
    }

    /// A child has ended: its outputs stamped, or the reason it failed recorded.
    void finish(pid_t pid, int wait_status) {
        const RunningChild r = running_[pid];
        running_.erase(pid);
        Job& job = jobs_[r.job];
        job.seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
        const fs::path dir = object_dir(plan_, job);
        if (WIFSIGNALED(wait_status)) remove_child_temporaries(dir, pid);
        if (WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 0) {
            try {
                const StampCounts counts = write_stamp(
                    dir,
                    {job.mesh_sha256, dictionary_.sha256, options_digest(o_, dictionary_, job)},
                    job.object->id, job.object->mesh, job.base);
                job.texels = counts.texels;
                job.textures = counts.textures;
                job.status = Status::Ok;
            } catch (const std::exception& e) {
                job.status = Status::Failed;
                job.reason = std::string("cannot stamp the outputs: ") + e.what();
            }
        } else if (g_batch_stop_signal != 0) {  // stopped by the batch, or by the terminal's ^C
            job.status = Status::NotRun;
            job.reason = "interrupted";
            return;
        } else {
            job.status = Status::Failed;
            job.reason = r.terminated
                             ? "timed out after " + duration_text(o_.timeout) + " (--timeout)"
                             : failure_reason(log_path(plan_, job), wait_status);
        }
        ended(job);
    }

    void enforce_timeouts() {
        const auto now = Clock::now();
        for (auto& [child, r] : running_) {
            if (!r.terminated && o_.timeout > 0 &&
                std::chrono::duration<double>(now - r.start).count() > o_.timeout)
                terminate(child, r);
            else if (r.terminated && now - r.terminated_at > std::chrono::seconds(5))
                ::kill(child, SIGKILL);
        }
    }

    const BatchOptions& o_;
    const BatchPlan& plan_;
    const Dictionary& dictionary_;
    std::vector<Job>& jobs_;
    BatchProgress& progress_;
    std::size_t done_, failed_;
    std::map<pid_t, RunningChild> running_;
};

}  // namespace

std::size_t run_children(const BatchOptions& o, const BatchPlan& plan, const Dictionary& dictionary,
                         std::vector<Job>& jobs, BatchProgress& progress,
                         const std::vector<std::size_t>& queue, std::size_t done,
                         std::size_t failed) {
    return Scheduler(o, plan, dictionary, jobs, progress, done, failed).run(queue);
}

}  // namespace geotex::cli
