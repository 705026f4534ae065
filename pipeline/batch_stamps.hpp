#pragma once
// The outputs of one batch object (OUTDIR/objects/<id>/) and its stamp, run.json: which mesh,
// dictionary and options made them and the digest of each, so that a rerun skips an object
// whose outputs are complete and unchanged (docs/collections.md, "Resuming"). Writing the
// stamp into place (atomically, refusing planted links) is the caller's: geotex batch.

#include <filesystem>
#include <optional>
#include <string>

namespace geotex {

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
    std::string mesh_sha256;        ///< digest of the mesh file's bytes
    std::string dictionary_sha256;  ///< digest of the dictionary's bytes
    std::string options_sha256;     ///< stamp_options_sha256 of the options
};

/// The options part of a stamp's key: SHA-256 of the geotex `version`, `options_text` (every
/// option that shapes the outputs, in a fixed text form of the caller's) and the names of the
/// outputs, so that a new version, another option or another set of outputs makes every
/// object stale.
std::string stamp_options_sha256(const std::string& options_text, const std::string& version);

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

/// A stamp and the counts it records.
struct Stamp {
    std::string text;  ///< the content of run.json (JSON, two-space indentation, final newline)
    StampCounts counts;
};

/// The stamp of `dir` once its outputs are all in place: their digests, and the counts read
/// from report.json. `id` is the object's, `mesh` its mesh as the manifest names it,
/// `graph_base` its --base ("" when none: its named graph is then the mesh's hash name).
/// Throws IoError naming the file when an output cannot be read; a report.json that is not
/// the JSON report throws nlohmann::json's exception.
Stamp make_stamp(const std::filesystem::path& dir, const StampKey& key, const std::string& id,
                 const std::string& mesh, const std::string& graph_base);

}  // namespace geotex
