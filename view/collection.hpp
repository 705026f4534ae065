#pragma once
/// What `geotex view PATH` shows: the objects of a `geotex batch` output directory (the rows
/// of its summary CSVs) or the one object whose outputs PATH holds, with their reports read,
/// and the only way the server reads an object's files (view/README.md, "What PATH is" and
/// "Files").

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace geotex::view {

/// One object of PATH.
struct ViewObject {
    std::string id;
    std::string status;  ///< the summary's status ("ok", "skipped", "failed"); "ok" alone
    int texels = -1;     ///< -1: unknown
    int textures = -1;   ///< -1: unknown
    std::string reason;  ///< the summary's reason, "" when none
    std::string error;   ///< non-empty: its files are missing or corrupt (one line)
    bool has_geometry = false;  ///< geometry.cbor is there (it can be re-annotated)
    /// report.json as read, without the texels' face lists (the mesh carries them); null when
    /// `error` is set.
    nlohmann::json report;
};

/// PATH, loaded.
struct ViewCollection {
    std::string root;    ///< PATH made absolute and canonical (a link as PATH is followed once)
    std::string name;    ///< PATH's last component
    bool single = false; ///< PATH is one object's outputs, not a batch output directory
    std::vector<ViewObject> objects;  ///< in id order

    /// The object with this id, or nullptr (also for an id that may name no directory).
    const ViewObject* find(const std::string& id) const;
};

/// The files of an object that the server may read.
enum class ObjectFile { Report, Segmentation, Geometry, Run };

/// The file name of `file` ("report.json", ...).
const char* file_name(ObjectFile file);

/// Loads PATH. Throws InvalidInput, one line naming PATH and what is missing, when PATH is
/// neither a batch output directory (summary.csv or summary-shard-*.csv, and objects/) nor a
/// directory holding report.json and segmentation.ply; ParseError for a summary that is no
/// CSV. An object whose report is missing or corrupt gets its `error`; the others load.
ViewCollection load_view_collection(const std::string& path);

/// The bytes of `file` of `object`, read without following any symbolic link below PATH
/// (each directory and the file opened with O_NOFOLLOW relative to the one above), and only
/// when it is a regular file. Throws IoError naming the file (relative to PATH) otherwise.
std::string read_object_file(const ViewCollection& collection, const ViewObject& object,
                             ObjectFile file);

/// True when read_object_file would open `file` of `object` (it is there, a regular file
/// reached without a link).
bool has_object_file(const ViewCollection& collection, const ViewObject& object, ObjectFile file);

}  // namespace geotex::view
