#pragma once
// What the parts of geotex batch share: its options, the plan that follows from them, and
// one job per object with its status. Internal to cli/ (cmd_batch.cpp, batch_plan.cpp,
// batch_scheduler.cpp, batch_progress.cpp).

#include <atomic>
#include <filesystem>
#include <string>

#include "annotation/significance.hpp"
#include "cli/collection.hpp"
#include "cli/commands.hpp"
#include "cli/segment_run.hpp"

namespace geotex::cli {

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

/// "ok", "skipped", "failed", "not run": a status as summary.csv writes it.
const char* status_name(Status s);

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

/// The batch's settings that follow from its options, checked before anything is read.
struct BatchPlan {
    int shard = 1, num_shards = 1;
    std::filesystem::path out_dir;
    std::string summary_path;
    int job_slots = 1;  ///< children at once
    int threads = 1;    ///< worker threads of each child
};

/// OUTDIR/objects/<id>: where the object's outputs go.
std::filesystem::path object_dir(const BatchPlan& plan, const Job& job);

/// OUTDIR/logs/<id>.log: the stderr of the object's child.
std::string log_path(const BatchPlan& plan, const Job& job);

/// The signal that stops the batch (SIGINT, SIGTERM, SIGHUP), 0 until one came. Set by the
/// batch's handler; read by the steps that wait (hashing a mesh, the scheduler).
extern std::atomic<int> g_batch_stop_signal;

}  // namespace geotex::cli
