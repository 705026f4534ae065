#pragma once
// The objects of a `geotex batch` output directory, as their run.json stamps describe them
// (docs/collections.md). Read by `geotex publish`.

#include <optional>
#include <string>
#include <vector>

namespace geotex::cli {

/// A complete object: its run.json stamp, read and checked.
struct BatchObject {
    std::string id;                 ///< its directory name under objects/ (= run.json "id")
    std::string dir;                ///< OUTDIR/objects/<id>
    std::string graph;              ///< run.json "graph": the named graph of its triples
    std::string annotation_path;    ///< dir/annotation.ttl
    std::string annotation_sha256;  ///< run.json outputs["annotation.ttl"]
};

/// An object left out, and why (no run.json yet, a file that does not match it).
struct IncompleteObject {
    std::string id;
    std::string reason;
};

struct BatchObjects {
    std::vector<BatchObject> complete;         ///< sorted by id (bytes)
    std::vector<IncompleteObject> incomplete;  ///< sorted by id
};

/// Lists the objects of OUTDIR. An object is complete when its run.json exists, the
/// annotation.ttl has the SHA-256 recorded there and every other file it lists exists (they
/// are not re-hashed: publishing reads only the annotation). Throws CliError (input) when
/// OUTDIR is missing or has no objects/ directory, or for a run.json that exists but cannot
/// be read or is no batch-object stamp of schema 1: the stamp is written last and whole, so
/// a bad one is no object still being written.
BatchObjects list_batch_objects(const std::string& outdir);

/// The object's annotation.ttl, if it still has the recorded digest; else nullopt with
/// `reason` set (the file changed since list_batch_objects, e.g. a batch run rewrote it).
std::optional<std::string> read_verified_annotation(const BatchObject& object, std::string& reason);

}  // namespace geotex::cli
