// geotex batch: a whole collection annotated into one output directory (docs/collections.md).
// Each object runs in a child process, forked to run what `geotex annotate` runs
// (annotate_object): a mesh that crashes or exhausts memory takes only itself down, memory
// stays flat however large the collection, a timeout can kill it, and --jobs children use
// the cores. The parent lists, skips what is up to date, schedules,
// stamps each finished object and writes the summary.

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <thread>

#include "annotation/digest.hpp"
#include "cli/annotate_object.hpp"
#include "cli/batch_children.hpp"
#include "cli/collection.hpp"
#include "cli/commands.hpp"
#include "cli/description_options.hpp"
#include "cli/dictionary_input.hpp"
#include "cli/segment_run.hpp"
#include "common/detail/csv.hpp"
#include "common/detail/text.hpp"
#include "ontology/rdf_writer.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/batch_stamps.hpp"
#include "pipeline/parameters_json.hpp"

namespace geotex::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct BatchOptions {
    CommonOptions common;
    SegmentRunOptions run;
    std::string input;
    std::string output;
    int jobs = 0;
    std::string shard;
    std::string base_template;
    std::string object_template;
    std::string creator;
    std::string mesh_unit;
    std::string dictionary;
    std::string lang = "en";
    DescriptionParams description;
    double timeout = 0;
    bool force = false;
};

enum class Status { Ok, Skipped, Failed, NotRun };

const char* status_name(Status s) {
    switch (s) {
        case Status::Ok:
            return "ok";
        case Status::Skipped:
            return "skipped";
        case Status::Failed:
            return "failed";
        case Status::NotRun:
            return "not run";
    }
    return "?";
}

struct Job {
    const CollectionObject* object = nullptr;
    Status status = Status::NotRun;
    double seconds = 0;
    long texels = -1;
    long textures = -1;
    std::string reason;
    std::string mesh_sha256;
    std::string base;
    std::string object_iri;  ///< the manifest's cell, else --object-template expanded, else ""
    std::string mesh_unit;   ///< the manifest's cell, else --mesh-unit, else ""
};

std::atomic<int> g_stop_signal{0};
extern "C" void batch_stop(int sig) { g_stop_signal = sig; }

/// "i/N" with 1 <= i <= N.
std::pair<int, int> parse_shard(const std::string& text) {
    static const std::regex kShard(R"(^\s*(\d{1,6})\s*/\s*(\d{1,6})\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, kShard))
        throw CliError(kExitUsage,
                       "--shard: '" + detail::printable(text) + "' is not i/N (e.g. 2/8)");
    const int i = std::stoi(m[1]), n = std::stoi(m[2]);
    if (n < 1 || i < 1 || i > n)
        throw CliError(kExitUsage, "--shard " + text + ": shards are numbered 1 to N (got " +
                                       std::to_string(i) + " of " + std::to_string(n) + ")");
    return {i, n};
}

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

const char* file_type_name(mode_t mode) {
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISDIR(mode)) return "a directory";
    return "no regular file";
}

/// SHA-256 of an object's mesh, refusing what is no regular file (a FIFO would block, a
/// device such as /dev/zero never ends) before opening it, and giving up after `timeout`
/// seconds (0: never). Returns "" when the batch is stopped meanwhile. Throws CliError
/// (input).
std::string hash_mesh(const std::string& path, double timeout) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw CliError(kExitInput, path + ": cannot open (" + std::strerror(errno) + ")");
    if (!S_ISREG(st.st_mode))
        throw CliError(kExitInput, path + ": is " + std::string(file_type_name(st.st_mode)) +
                                       ", not a regular file: a mesh must be a file");
    // O_NONBLOCK: should the name have become a FIFO since the stat, the open cannot block.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) throw CliError(kExitInput, path + ": cannot open (" + std::strerror(errno) + ")");
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
        throw CliError(kExitInput, path + ": is not a regular file: a mesh must be a file");
    const auto start = Clock::now();
    Sha256 hash;
    std::string chunk(1 << 20, '\0');
    for (;;) {
        if (g_stop_signal != 0) return {};
        if (timeout > 0 && std::chrono::duration<double>(Clock::now() - start).count() > timeout)
            throw CliError(kExitInput, path + ": timed out after " + duration_text(timeout) +
                                           " while reading the mesh (--timeout)");
        const ssize_t n = ::read(fd, chunk.data(), chunk.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0)
            throw CliError(kExitInput, path + ": read failed (" + std::strerror(errno) + ")");
        if (n == 0) break;
        hash.update(std::string_view(chunk).substr(0, static_cast<std::size_t>(n)));
    }
    return hash.hex();
}

/// What makes the outputs of an object what they are, besides the mesh and dictionary bytes.
/// The dictionary's name is among them: the JSON report records it.
std::string options_digest(const BatchOptions& o, const Dictionary& dictionary, const Job& job) {
    return stamp_options_sha256(parameters_json(o.run.params, 0).dump() +
                                    "\ndictionary=" + dictionary.source_name + "\nlang=" + o.lang +
                                    "\n" + description_params_text(o.description) +
                                    "\nbase=" + job.base + "\nobject=" + job.object_iri +
                                    "\ncreator=" + o.creator + "\nmesh_unit=" + job.mesh_unit,
                                version());
}

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

class BatchProgress {
  public:
    BatchProgress(bool quiet, std::size_t total)
        : quiet_(quiet), tty_(::isatty(STDERR_FILENO) != 0), total_(total) {}

    void finished(const Job& job, std::size_t done, std::size_t failed) {
        if (job.status == Status::Failed) {
            clear();
            // The reason names the file or the manifest row; the id leads when it helps.
            const bool id_in_reason = job.reason.find(job.object->id) != std::string::npos;
            warn((id_in_reason || job.object->id.empty()
                      ? ""
                      : detail::printable(job.object->id) + ": ") +
                 job.reason);
        } else if (!quiet_ && !tty_) {
            std::fprintf(stderr, "geotex: [%zu/%zu] %s %s %.2f s (%ld texels, %ld textures)\n",
                         done, total_, job.object->id.c_str(), status_name(job.status), job.seconds,
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

    /// The bar on a terminal: done/total, failures, running, ETA from the objects run so far.
    void draw(std::size_t running, bool force = false) {
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

    void clear() {
        if (drawn_) std::fprintf(stderr, "\r%*s\r", 100, "");
        drawn_ = false;
    }

    void skipped_before_start(std::size_t n) {
        skipped_at_start_ = n;
        done_ = n;
        start_ = Clock::now();
    }

  private:
    bool quiet_, tty_;
    std::size_t total_, done_ = 0, failed_ = 0, ran_ = 0, skipped_at_start_ = 0;
    double run_seconds_ = 0;
    bool drawn_ = false;
    Clock::time_point start_ = Clock::now(), last_draw_{};
};

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

/// Throws CliError when `dir` exists and is no directory (a link planted at objects/<id> is
/// never followed, not even to read a stamp).
void refuse_non_directory(const fs::path& dir) {
    struct stat st {};
    if (::lstat(dir.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
        throw CliError(
            kExitOutput,
            dir.string() + (S_ISLNK(st.st_mode) ? ": is a symbolic link; geotex does not write "
                                                  "through links inside an output directory"
                                                : ": is not a directory"));
}

void make_directory(const fs::path& dir) {
    refuse_non_directory(dir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw CliError(kExitOutput, dir.string() + ": cannot create the directory (" +
                                        (ec ? ec.message() : "not a directory") + ")");
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
        throw CliError(kExitOutput, dir.string() + ": cannot write in the directory (" +
                                        std::strerror(errno) + ")");
}

/// The batch's settings that follow from its options, checked before anything is read.
struct BatchPlan {
    int shard = 1, num_shards = 1;
    fs::path out_dir;
    std::string summary_path;
    int job_slots = 1;  ///< children at once
    int threads = 1;    ///< worker threads of each child
};

/// Checks everything that needs no mesh, so a typo costs nothing. Throws CliError.
BatchPlan check_batch_options(BatchOptions& o) {
    BatchPlan plan;
    if (!o.shard.empty()) std::tie(plan.shard, plan.num_shards) = parse_shard(o.shard);
    if (!o.base_template.empty()) {
        const std::string sample =
            expand_iri_template("--base-template", o.base_template, "object", std::string(64, '0'));
        in_phase(kExitUsage, "--base-template", [&] { return validate_base_iri(sample); });
    }
    if (!o.object_template.empty()) {
        const std::string sample = expand_iri_template("--object-template", o.object_template,
                                                       "object", std::string(64, '0'));
        in_phase(kExitUsage, "--object-template",
                 [&] { return validate_iri(sample, "object IRI"); });
    }
    if (!o.creator.empty())
        in_phase(kExitUsage, "--creator", [&] { return validate_iri(o.creator, "creator IRI"); });
    checked_mesh_unit(o.mesh_unit);
    if (!detail::is_language_tag(o.lang))
        throw CliError(kExitUsage,
                       "--lang: '" + o.lang + "' is not a language tag (e.g. en, fr, pt-BR)");
    if (!(o.timeout >= 0) || !std::isfinite(o.timeout))
        throw CliError(kExitUsage, "--timeout must be a number of seconds >= 0 (0: none)");
    check_segmentation_options(o.run);
    if (o.output.empty()) throw CliError(kExitUsage, "--output: empty directory name");
    plan.out_dir = fs::path(o.output);
    plan.summary_path =
        (plan.out_dir / (plan.num_shards == 1
                             ? std::string("summary.csv")
                             : "summary-shard-" + std::to_string(plan.shard) + "-of-" +
                                   std::to_string(plan.num_shards) + ".csv"))
            .string();
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    plan.job_slots = o.jobs > 0 ? o.jobs : static_cast<int>(cores);
    plan.threads = o.common.threads > 0 ? o.common.threads
                                        : std::max(1, static_cast<int>(cores) / plan.job_slots);
    return plan;
}

/// Every input of the batch: no output may be one of them (a manifest row naming the
/// segmentation of another object, a summary over the manifest).
InputFiles batch_inputs(const BatchOptions& o, const Collection& collection) {
    InputFiles inputs{{"collection", o.input}, {"--dictionary", o.dictionary}};
    for (const auto& object : collection.objects)
        if (!object.path.empty())
            inputs.add(
                {"mesh of object '" + detail::printable(object.id) + "' (" + object.where + ")",
                 object.path});
    return inputs;
}

/// The objects of this shard, in the collection's order. An object without a usable id is
/// reported by shard 1 only, so exactly once.
std::vector<Job> shard_jobs(const Collection& collection, const BatchPlan& plan) {
    std::vector<Job> jobs;
    for (const auto& object : collection.objects) {
        const bool usable_id = check_object_id(object.id).empty();
        if ((usable_id ? shard_of(object.id, plan.num_shards) : 1) != plan.shard) continue;
        Job job;
        job.object = &object;
        jobs.push_back(job);
    }
    return jobs;
}

fs::path object_dir(const BatchPlan& plan, const Job& job) {
    return plan.out_dir / "objects" / job.object->id;
}

std::string log_path(const BatchPlan& plan, const Job& job) {
    return (plan.out_dir / "logs" / (job.object->id + ".log")).string();
}

/// Decides what `job` needs before anything runs: Failed (an unreadable mesh, an output
/// that may not be written), Skipped (its stamp matches: up to date) or still NotRun (to
/// run). Fills the digest, IRIs and unit of the job. Returns false when the batch is stopped
/// meanwhile.
bool prepare_job(const BatchOptions& o, const BatchPlan& plan, const Dictionary& dictionary,
                 const InputFiles& inputs, Job& job) {
    const auto start = Clock::now();
    const fs::path dir = object_dir(plan, job);
    if (!job.object->error.empty()) {
        job.status = Status::Failed;
        job.reason = job.object->error;
        return true;
    }
    try {
        job.mesh_sha256 = hash_mesh(job.object->path, o.timeout);
        if (job.mesh_sha256.empty()) return false;  // stopped
        refuse_non_directory(dir);
    } catch (const CliError& e) {
        job.status = Status::Failed;
        job.reason = e.what();
        return true;
    }
    if (!o.base_template.empty())
        job.base = expand_iri_template("--base-template", o.base_template, job.object->id,
                                       job.mesh_sha256);
    job.object_iri = job.object->object_iri;
    if (job.object_iri.empty() && !o.object_template.empty())
        job.object_iri = expand_iri_template("--object-template", o.object_template, job.object->id,
                                             job.mesh_sha256);
    job.mesh_unit = job.object->mesh_unit.empty() ? o.mesh_unit : job.object->mesh_unit;
    const StampKey key{job.mesh_sha256, dictionary.sha256, options_digest(o, dictionary, job)};
    if (const auto counts = o.force ? std::optional<StampCounts>() : up_to_date_stamp(dir, key)) {
        job.texels = counts->texels;
        job.textures = counts->textures;
        job.status = Status::Skipped;
        job.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        return true;
    }
    // What the object will write: never through a link planted in OUTDIR, never over an
    // input of the batch (another row's mesh, the manifest, the dictionary).
    std::vector<OutputPath> outputs;
    for (const auto& out : kObjectOutputs)
        outputs.push_back({"output", (dir / out.file).string(), false, true});
    outputs.push_back({"stamp", (dir / kStampFile).string(), false, true});
    outputs.push_back({"log", log_path(plan, job), false, true});
    std::error_code ec;
    if (!fs::exists(dir, ec))
        outputs.erase(outputs.begin(), outputs.end() - 1);  // only the log exists yet
    try {
        check_output_paths(outputs, inputs);
    } catch (const CliError& e) {
        job.status = Status::Failed;
        job.reason = e.what();
    }
    return true;
}

/// What a child runs: `geotex annotate` of the object into its directory, with the batch's
/// options and dictionary. The outputs refuse links: one planted after prepare_job's check
/// is still not followed.
AnnotateJob annotate_job(const BatchOptions& o, const BatchPlan& plan, const Dictionary& dictionary,
                         const Job& job) {
    AnnotateJob a;
    a.common.threads = plan.threads;
    a.run = o.run;
    a.run.mesh = job.object->path;
    a.dictionary = o.dictionary;
    a.loaded_dictionary = &dictionary;
    a.base = job.base;
    a.object = job.object_iri;
    a.creator = o.creator;
    a.mesh_unit = job.mesh_unit;
    a.lang = o.lang;
    a.description = o.description;
    a.refuse_output_links = true;
    const fs::path dir = object_dir(plan, job);
    const std::map<std::string, std::string AnnotateJob::*> file_of_option = {
        {"--output", &AnnotateJob::output},
        {"--json", &AnnotateJob::json},
        {"--jsonld", &AnnotateJob::jsonld},
        {"--segmentation", &AnnotateJob::segmentation},
        {"--geometry-cache", &AnnotateJob::geometry_cache}};
    for (const auto& out : kObjectOutputs)
        a.*file_of_option.at(out.option) = (dir / out.file).string();
    return a;
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
        while ((next < queue.size() && g_stop_signal == 0) || !running_.empty()) {
            while (g_stop_signal == 0 && next < queue.size() &&
                   static_cast<int>(running_.size()) < plan_.job_slots)
                start(queue[next++]);
            if (g_stop_signal != 0)
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
        } else if (g_stop_signal != 0) {  // stopped by the batch, or by the terminal's ^C
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

/// The last line on stdout: what was done, and where the summary is.
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
    for (std::size_t i = 0; i < jobs.size() && g_stop_signal == 0; ++i) {
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
    failed = Scheduler(o, plan, dictionary, jobs, progress, done, failed).run(queue);
    progress.clear();
    if (g_stop_signal != 0)
        for (Job& j : jobs)
            if (j.status == Status::NotRun && j.reason.empty()) j.reason = "interrupted";
    write_summary(plan.summary_path, jobs);
    print_totals(o, plan, jobs, std::chrono::duration<double>(Clock::now() - batch_start).count());
    if (g_stop_signal != 0) {
        const int sig = g_stop_signal;
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
