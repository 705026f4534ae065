#pragma once
// The outputs of one batch object (OUTDIR/objects/<id>/) and its stamp, run.json: which mesh,
// dictionary and options made them and the digest of each, so that a rerun skips an object
// whose outputs are complete and unchanged (docs/collections.md, "Resuming").

#include <filesystem>
#include <optional>
#include <string>

namespace geotex::cli {

/// An output of an object: its file name in objects/<id>/ and the annotate option writing it.
struct ObjectOutput {
    const char* file;
    const char* option;
};
inline constexpr ObjectOutput kObjectOutputs[] = {{"annotation.ttl", "--output"},
                                                  {"report.json", "--json"},
                                                  {"annotation.jsonld", "--jsonld"},
                                                  {"segmentation.ply", "--segmentation"},
                                                  {"geometry.cbor", "--geometry-cache"}};
inline constexpr const char* kStampFile = "run.json";

/// What a stamp must match for the object to be up to date.
struct StampKey {
    std::string mesh_sha256;
    std::string dictionary_sha256;
    std::string options_sha256;
};

/// The counts a stamp records.
struct StampCounts {
    long texels = -1;
    long textures = -1;
};

/// A regular file that is no symbolic link: what geotex itself wrote into OUTDIR. Anything
/// else there (a planted link, a FIFO) is never opened.
bool is_plain_file(const std::filesystem::path& path);

/// The counts of `dir`'s stamp when it matches `key` and every output still has the digest
/// recorded; nothing when the object must run (no stamp, another key, an output changed or
/// missing, an unreadable or foreign stamp).
std::optional<StampCounts> up_to_date_stamp(const std::filesystem::path& dir, const StampKey& key);

/// Writes `dir`'s stamp (atomically, refusing a planted link) once the child's outputs are
/// all in place, and returns the counts read from report.json. `graph_base` is the object's
/// --base ("" when none: its named graph is then the mesh's hash name).
StampCounts write_stamp(const std::filesystem::path& dir, const StampKey& key, const std::string& id,
                        const std::string& mesh, const std::string& graph_base);

}  // namespace geotex::cli
