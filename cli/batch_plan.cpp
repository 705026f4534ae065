// geotex batch before anything runs (batch_plan.hpp).

#include "cli/batch_plan.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <string_view>
#include <thread>

#include "annotation/digest.hpp"
#include "cli/batch_progress.hpp"
#include "cli/description_options.hpp"
#include "common/detail/text.hpp"
#include "ontology/rdf_writer.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/batch_stamps.hpp"
#include "pipeline/parameters_json.hpp"
#include "pipeline/scale_report.hpp"

namespace geotex::cli {

namespace fs = std::filesystem;

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

fs::path object_dir(const BatchPlan& plan, const Job& job) {
    return plan.out_dir / "objects" / job.object->id;
}

std::string log_path(const BatchPlan& plan, const Job& job) {
    return (plan.out_dir / "logs" / (job.object->id + ".log")).string();
}

namespace {

using Clock = std::chrono::steady_clock;

/// One number of --shard: 1 to 6 digits, spaces around allowed.
bool shard_number(std::string_view part, int& value) {
    const auto first = part.find_first_not_of(" \t");
    const auto last = part.find_last_not_of(" \t");
    if (first == std::string_view::npos) return false;
    part = part.substr(first, last - first + 1);
    if (part.size() > 6) return false;
    for (const char c : part)
        if (c < '0' || c > '9') return false;
    return std::from_chars(part.data(), part.data() + part.size(), value).ec == std::errc();
}

}  // namespace

std::pair<int, int> parse_shard(const std::string& text) {
    const std::string_view view(text);
    const auto slash = view.find('/');
    int i = 0, n = 0;
    if (slash == std::string_view::npos || !shard_number(view.substr(0, slash), i) ||
        !shard_number(view.substr(slash + 1), n))
        throw CliError(kExitUsage,
                       "--shard: '" + detail::printable(text) + "' is not i/N (e.g. 2/8)");
    if (n < 1 || i < 1 || i > n)
        throw CliError(kExitUsage, "--shard " + text + ": shards are numbered 1 to N (got " +
                                       std::to_string(i) + " of " + std::to_string(n) + ")");
    return {i, n};
}

namespace {

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
        if (g_batch_stop_signal != 0) return {};
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

}  // namespace

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

InputFiles batch_inputs(const BatchOptions& o, const Collection& collection) {
    InputFiles inputs{{"collection", o.input}, {"--dictionary", o.dictionary}};
    for (const auto& object : collection.objects)
        if (!object.path.empty())
            inputs.add(
                {"mesh of object '" + detail::printable(object.id) + "' (" + object.where + ")",
                 object.path});
    return inputs;
}

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

std::string options_digest(const BatchOptions& o, const Dictionary& dictionary, const Job& job) {
    // With --scale auto the scale is each object's own: the stamp holds the rule's series.
    const std::string scale =
        o.run.auto_scale ? "\nscale=auto " + scale_series_json(ScaleSeries{}, o.run.series).dump() +
                               (o.run.levels ? "\nlevels" : "")
                         : std::string();
    return stamp_options_sha256(parameters_json(o.run.params, 0).dump() + scale +
                                    "\ndictionary=" + dictionary.source_name + "\nlang=" + o.lang +
                                    "\n" + description_params_text(o.description) +
                                    "\nbase=" + job.base + "\nobject=" + job.object_iri +
                                    "\ncreator=" + o.creator + "\nmesh_unit=" + job.mesh_unit,
                                version());
}

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

}  // namespace geotex::cli
