#pragma once
/// The JSON bodies of the workbench's HTTP API (view/README.md, "HTTP API"), built from the
/// loaded collection and the dictionary in use, with no server involved, so that each body is
/// testable alone. Numbers that are not finite are null, as in geotex's reports.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/dictionary_edit.hpp"
#include "annotation/dictionary_fit.hpp"
#include "annotation/significance.hpp"
#include "pipeline/loaded_collection.hpp"

namespace geotex::view {

/// What the session says of the dictionary in use.
struct DictionaryInUse {
    const Dictionary* dictionary = nullptr;  ///< parsed; never null when serving
    std::string file;                        ///< --dictionary FILE's name; "" for the default
    bool editable = false;                   ///< --dictionary given: saving is allowed
};

/// GET /api/session: geotex's version, PATH's name, the feature ids in column order and the
/// dictionary (file name or null, editable, id, version).
nlohmann::json session_json(const LoadedCollection& collection, const DictionaryInUse& dictionary);

/// C: one concept, infinite bounds as null.
nlohmann::json concept_json(const DictionaryConcept& c);

/// The concepts of a dictionary, in its order.
nlohmann::json concepts_json(const Dictionary& dictionary);

/// The textures (T) of an object from its report's "annotation" (or `annotation`, the
/// "annotation" member of a report made anew, when not null): colour, orientation ("raised"
/// or "engraved"), texel count, chosen and withheld concepts with their bounds in
/// `dictionary`.
nlohmann::json textures_json(const LoadedObject& object, const Dictionary& dictionary,
                             const nlohmann::json& annotation = nullptr);

/// GET /api/objects: one entry per object (id, status, counts, reason, error, reannotate and
/// the concept ids of its textures' chosen words, sorted and unique).
nlohmann::json objects_json(const LoadedCollection& collection);

/// GET /api/objects/<id>: faces, vertices, textures (T) and texels (X: features, the
/// significance of each feature in the texel's texture, and the concept of `dictionary` whose
/// interval holds each value). An object with an error gives only its id and error.
nlohmann::json object_json(const LoadedObject& object, const Dictionary& dictionary);

/// GET /api/features: for each feature id, its values over the texels and over the textures
/// of every object without error (null where undefined).
nlohmann::json features_json(const LoadedCollection& collection);

/// The depth_mean of each texel of a report, NaN where null: the depth of the GTXM mesh.
std::vector<double> texel_depths(const nlohmann::json& report);

/// The object with this id, or nullptr (also for an id that may name no directory).
const LoadedObject* find_object(const LoadedCollection& collection, const std::string& id);

/// PATH's name as the session gives it: the last component of the collection's path.
std::string collection_name(const LoadedCollection& collection);

/// The "annotation" member a report would hold for `descriptions` (describe_textures'
/// result): per texture its chosen and withheld concepts (feature, concept) and features
/// (feature, value, significance), what textures_json reads.
nlohmann::json annotation_json(const std::vector<TextureDescription>& descriptions);

/// E: the edits of a request body's "edits". Throws InvalidInput ("edit 2: ...") for one that
/// is not an edit of view/README.md.
std::vector<DictionaryEdit> edits_from_json(const nlohmann::json& edits);

/// E of one edit.
nlohmann::json edit_json(const DictionaryEdit& edit);

/// The marks of POST /api/fit's body: its "marks", each {"object", "texture", "concept",
/// "yes"}. Throws InvalidInput ("mark 2: ...") for one that is not a mark.
std::vector<FitMark> marks_from_json(const nlohmann::json& body);

/// The answer of POST /api/fit: {"edits": [E], "unsatisfied": [...]}, the marks no bound
/// satisfies followed by those the word rule still does not reproduce, each with its reason.
nlohmann::json fit_json(const DictionaryFitResult& fit);

/// `{"problems": [{"line", "column", "message"}]}`.
nlohmann::json problems_json(const std::vector<DictionaryProblem>& problems);

/// `{"error": message}`.
nlohmann::json error_json(const std::string& message);

}  // namespace geotex::view
