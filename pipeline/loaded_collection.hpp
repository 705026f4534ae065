#pragma once
/// The annotated objects that the workbench (`geotex view`) and `geotex dict fit` load from
/// PATH, a `geotex batch` output directory or one object's outputs directory
/// (view/README.md, "What PATH is"), and the words they get again under another dictionary
/// without the geometric stages: the texel features come from each object's geometry.cbor.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/dictionary_fit.hpp"
#include "annotation/significance.hpp"
#include "pipeline/geometry_cache.hpp"

namespace geotex {

/// Whether `id` may name an object's directory: not empty, no '/', no NUL, not starting with
/// '.' (so neither "." nor ".." nor a hidden file).
bool is_object_id(std::string_view id);

/// The bytes of `root`/`id`/`name`, read without following a symbolic link: the object's
/// directory and the file are opened with O_NOFOLLOW relative to `root` (so the real path
/// stays under `root`), and only a regular file is read. `name` is a plain file name.
/// Throws InvalidInput for an id or name that is refused, IoError naming the file when it is
/// absent, a link, not a regular file, or unreadable.
std::string read_object_file(const std::string& root, const std::string& id,
                             const std::string& name);

/// A texture's chosen words: the concept ids, in the order of the choice (by rank).
using TextureWords = std::vector<std::string>;
/// An object's words: one entry per texture, in texture order.
using ObjectWords = std::vector<TextureWords>;

/// One object of a loaded collection.
struct LoadedObject {
    std::string id;
    std::string status = "ok";  ///< summary.csv: ok, skipped, failed or not run ("ok" for
                                ///< one object's directory)
    long texels = -1;           ///< summary.csv (report.json for one object's directory);
    long textures = -1;         ///< -1 when unknown (a failed object's empty cells)
    std::string reason;       ///< summary.csv's reason of a failure
    std::string error;        ///< why the object cannot be shown, one line naming the file; "" when
                              ///< it loaded
    bool reannotate = false;  ///< its geometry.cbor was read: reannotate() gives it new words
    nlohmann::json report;    ///< report.json, parsed (null when it could not be read)
    GeometryTables geometry;  ///< from geometry.cbor, when `reannotate`
    DescriptionParams params;       ///< the word choice the batch used (report.json
                                    ///< annotation.choice; the seed is not an option: the default)
    ObjectWords words;              ///< the words report.json holds, per texture
    std::string dictionary_sha256;  ///< of the dictionary the words came from (report.json)
};

/// What load_collection found at PATH.
struct LoadedCollection {
    std::string path;                   ///< PATH as given
    std::string objects_root;           ///< the directory holding the objects' directories
    bool batch = false;                 ///< a batch output (else one object's outputs)
    std::vector<LoadedObject> objects;  ///< in id order
};

/// Loads PATH: for a batch output, the rows of summary.csv and summary-shard-*.csv (id order;
/// an id in two files is taken from the first file by name), each object's report.json and
/// geometry.cbor read through read_object_file and checked against the digests its run.json
/// records; for one object's outputs (report.json and segmentation.ply in PATH), that object,
/// its id the directory's name. A failed or unstamped object, or one whose files are missing
/// or corrupt, gets an `error` and the others load. Throws InvalidInput naming PATH and what
/// is missing when PATH is neither kind, ParseError for a summary CSV that does not parse.
LoadedCollection load_collection(const std::string& path);

/// The words of `descriptions` (describe_textures' result), per texture.
ObjectWords chosen_words(const std::vector<TextureDescription>& descriptions);

/// The language of the labels report.json gives to the chosen words, found by comparing them
/// with the labels of `dictionary` (the one the words came from): the first of
/// dictionary.languages, then of the concepts' other languages, in which every recorded label
/// is the concept's label; "" when none fits (no words, or another dictionary).
std::string report_label_language(const nlohmann::json& report, const Dictionary& dictionary);

/// The words of every object under `dictionary`: describe_textures of its geometry tables
/// with its own params, one entry per object (empty for an object without `reannotate`).
/// Objects run in parallel (TBB); the result does not depend on the thread count. The
/// descriptions point into `dictionary`, which must outlive them.
std::vector<std::vector<TextureDescription>> reannotate(const LoadedCollection& collection,
                                                        const Dictionary& dictionary);

/// A texture whose chosen words differ.
struct WordChange {
    std::string object;  ///< object id
    int texture = -1;
    TextureWords before, after;
};

/// The textures whose chosen words differ between `before` and `after` (one ObjectWords per
/// object of `collection`, in its order; compared as sets of concept ids, listed in their
/// order of choice), in object then texture order. Objects without `reannotate` are skipped;
/// a texture present on one side only counts as changed. Throws InvalidInput when the sizes
/// are not one per object.
std::vector<WordChange> diff_words(const LoadedCollection& collection,
                                   const std::vector<ObjectWords>& before,
                                   const std::vector<ObjectWords>& after);

/// The words the collection's reports hold (LoadedObject::words), one per object.
std::vector<ObjectWords> report_words(const LoadedCollection& collection);

/// chosen_words of each object's descriptions.
std::vector<ObjectWords> chosen_words(
    const std::vector<std::vector<TextureDescription>>& descriptions);

/// The objects that fit_dictionary can read (those with `reannotate`), named by their ids.
std::vector<FitObject> fit_objects(const LoadedCollection& collection);

}  // namespace geotex
