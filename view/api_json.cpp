#include "view/api_json.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include "common/errors.hpp"
#include "geometry/feature_table.hpp"
#include "pipeline/annotate.hpp"

namespace geotex::view {

using Json = nlohmann::json;

namespace {

Json bound(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

int feature_column(const std::string& id) {
    for (int k = 0; k < kNumFeatures; ++k)
        if (id == kFeatureIds[static_cast<std::size_t>(k)]) return k;
    return -1;
}

const DictionaryConcept* find_concept(const Dictionary& d, const std::string& id) {
    for (const auto& c : d.concepts)
        if (c.id == id) return &c;
    return nullptr;
}

// The label a page shows for a concept: English, else the dictionary's first language, else
// what the report said.
std::string label_of(const DictionaryConcept* c, const Json& entry) {
    if (c != nullptr) {
        if (auto it = c->labels.find("en"); it != c->labels.end()) return it->second;
        if (!c->labels.empty()) return c->labels.begin()->second;
    }
    return entry.value("label", std::string());
}

// A chosen or withheld word of a texture, with its interval in the dictionary in use (null
// bounds when the dictionary no longer has the concept).
Json word_json(const Json& entry, const Dictionary& dictionary) {
    const std::string id = entry.value("concept", std::string());
    const DictionaryConcept* c = find_concept(dictionary, id);
    return Json{{"id", id},
                {"label", label_of(c, entry)},
                {"feature", entry.value("feature", std::string())},
                {"lower", c ? bound(c->lower) : Json(nullptr)},
                {"upper", c ? bound(c->upper) : Json(nullptr)}};
}

const Json& annotation_textures(const LoadedObject& o, const Json& annotation) {
    static const Json kNone = Json::array();
    if (!annotation.is_null()) {
        if (annotation.contains("textures") && annotation["textures"].is_array())
            return annotation["textures"];
        return kNone;
    }
    if (o.report.contains("annotation") && o.report["annotation"].is_object() &&
        o.report["annotation"].contains("textures") &&
        o.report["annotation"]["textures"].is_array())
        return o.report["annotation"]["textures"];
    return kNone;
}

double number(const Json& j) {
    return j.is_number() ? j.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

Json error_json(const std::string& message) { return Json{{"error", message}}; }

const LoadedObject* find_object(const LoadedCollection& collection, const std::string& id) {
    if (!is_object_id(id)) return nullptr;
    const auto it =
        std::lower_bound(collection.objects.begin(), collection.objects.end(), id,
                         [](const LoadedObject& o, const std::string& key) { return o.id < key; });
    return it != collection.objects.end() && it->id == id ? &*it : nullptr;
}

std::string collection_name(const LoadedCollection& collection) {
    std::filesystem::path p(collection.path);
    // "out/" names "out", as does "out/."
    while (!p.empty() && (p.filename().empty() || p.filename() == ".")) p = p.parent_path();
    const std::string name = p.filename().string();
    return name.empty() ? collection.path : name;
}

Json annotation_json(const std::vector<TextureDescription>& descriptions) {
    Json textures = Json::array();
    for (const TextureDescription& d : descriptions) {
        auto words = [&](const std::vector<int>& which) {
            Json out = Json::array();
            for (int i : which) {
                const FeatureScore& f = d.features[static_cast<std::size_t>(i)];
                if (f.concept_ptr == nullptr) continue;
                out.push_back(Json{{"feature", kFeatureIds[static_cast<std::size_t>(f.feature)]},
                                   {"concept", f.concept_ptr->id}});
            }
            return out;
        };
        Json features = Json::array();
        for (const FeatureScore& f : d.features)
            features.push_back(Json{{"feature", kFeatureIds[static_cast<std::size_t>(f.feature)]},
                                    {"value", bound(f.value)},
                                    {"significance", bound(f.significance)}});
        textures.push_back(Json{{"texture", d.texture},
                                {"concepts", words(d.chosen)},
                                {"withheld", words(d.withheld)},
                                {"features", features}});
    }
    return Json{{"textures", textures}};
}

std::vector<DictionaryEdit> edits_from_json(const Json& edits) {
    if (!edits.is_array()) throw InvalidInput("\"edits\" is not a list");
    std::vector<DictionaryEdit> out;
    for (std::size_t i = 0; i < edits.size(); ++i) {
        const Json& e = edits[i];
        const std::string where = "edit " + std::to_string(i + 1) + ": ";
        auto text = [&](const char* key) {
            if (!e.is_object() || !e.contains(key) || !e[key].is_string())
                throw InvalidInput(where + "no text \"" + key + "\"");
            return e[key].get<std::string>();
        };
        DictionaryEdit edit;
        const std::string op = text("op");
        edit.concept_id = text("concept");
        edit.value = text("value");
        if (op == "bound") {
            edit.kind = DictionaryEdit::Kind::Bound;
            const std::string side = text("side");
            if (side != "lower" && side != "upper")
                throw InvalidInput(where + "side is \"" + side + "\", not lower or upper");
            edit.upper = side == "upper";
        } else if (op == "label") {
            edit.kind = DictionaryEdit::Kind::Label;
            edit.language = text("lang");
        } else {
            throw InvalidInput(where + "op is \"" + op + "\", not bound or label");
        }
        out.push_back(std::move(edit));
    }
    return out;
}

std::vector<FitMark> marks_from_json(const Json& body) {
    const Json marks = body.is_object() && body.contains("marks") ? body["marks"] : Json();
    if (!marks.is_array()) throw InvalidInput("\"marks\" is not a list");
    std::vector<FitMark> out;
    for (std::size_t i = 0; i < marks.size(); ++i) {
        const Json& m = marks[i];
        const std::string where = "mark " + std::to_string(i + 1);
        if (!m.is_object() || !m.contains("object") || !m["object"].is_string() ||
            !m.contains("texture") || !m["texture"].is_number_integer() || !m.contains("concept") ||
            !m["concept"].is_string() || !m.contains("yes") || !m["yes"].is_boolean())
            throw InvalidInput(where +
                               ": needs object (text), texture (integer), concept (text) and "
                               "yes (true or false)");
        out.push_back(FitMark{m["object"].get<std::string>(), m["texture"].get<int>(),
                              m["concept"].get<std::string>(), m["yes"].get<bool>(), where});
    }
    return out;
}

Json fit_json(const DictionaryFitResult& fit) {
    Json edits = Json::array();
    for (const DictionaryEdit& e : fit.edits) edits.push_back(edit_json(e));
    Json unsatisfied = Json::array();
    for (const auto* list : {&fit.unsatisfied, &fit.not_reproduced})
        for (const FitProblem& p : *list)
            unsatisfied.push_back(Json{{"object", p.mark.object},
                                       {"texture", p.mark.texture},
                                       {"concept", p.mark.concept_id},
                                       {"yes", p.mark.yes},
                                       {"reason", p.reason}});
    return Json{{"edits", edits}, {"unsatisfied", unsatisfied}};
}

Json edit_json(const DictionaryEdit& edit) {
    if (edit.kind == DictionaryEdit::Kind::Label)
        return Json{{"op", "label"},
                    {"concept", edit.concept_id},
                    {"lang", edit.language},
                    {"value", edit.value}};
    return Json{{"op", "bound"},
                {"concept", edit.concept_id},
                {"side", edit.upper ? "upper" : "lower"},
                {"value", edit.value}};
}

Json problems_json(const std::vector<DictionaryProblem>& problems) {
    Json out = Json::array();
    for (const DictionaryProblem& p : problems)
        out.push_back(Json{{"line", p.line}, {"column", p.column}, {"message", p.message}});
    return Json{{"problems", out}};
}

Json session_json(const LoadedCollection& collection, const DictionaryInUse& in_use) {
    Json features = Json::array();
    for (const char* id : kFeatureIds) features.push_back(id);
    const Dictionary& d = *in_use.dictionary;
    return Json{{"geotex", version()},
                {"path", collection_name(collection)},
                {"features", features},
                {"dictionary",
                 {{"file", in_use.file.empty() ? Json(nullptr) : Json(in_use.file)},
                  {"editable", in_use.editable},
                  {"id", d.id},
                  {"version", d.version}}}};
}

Json concept_json(const DictionaryConcept& c) {
    Json labels = Json::object();
    for (const auto& [lang, text] : c.labels) labels[lang] = text;
    return Json{{"id", c.id},
                {"feature", c.feature >= 0 && c.feature < kNumFeatures
                                ? Json(kFeatureIds[static_cast<std::size_t>(c.feature)])
                                : Json(nullptr)},
                {"lower", bound(c.lower)},
                {"upper", bound(c.upper)},
                {"lower_text", c.lower_text},
                {"upper_text", c.upper_text},
                {"labels", labels},
                {"line", c.line}};
}

Json concepts_json(const Dictionary& dictionary) {
    Json out = Json::array();
    for (const auto& c : dictionary.concepts) out.push_back(concept_json(c));
    return out;
}

Json textures_json(const LoadedObject& object, const Dictionary& dictionary,
                   const Json& annotation) {
    const Json& words = annotation_textures(object, annotation);
    Json out = Json::array();
    if (!object.report.is_object()) return out;
    for (const Json& t : object.report["textures"]) {
        const int id = t.value("id", -1);
        Json concepts = Json::array(), withheld = Json::array();
        for (const Json& w : words) {
            if (w.value("texture", -2) != id) continue;
            for (const Json& e : w.value("concepts", Json::array()))
                concepts.push_back(word_json(e, dictionary));
            for (const Json& e : w.value("withheld", Json::array()))
                withheld.push_back(word_json(e, dictionary));
        }
        out.push_back(
            Json{{"id", id},
                 {"colour", t.value("colour", std::string())},
                 {"orientation",
                  t.value("orientation", std::string()) == "negative" ? "engraved" : "raised"},
                 {"texels", t.value("texel_count", 0)},
                 {"concepts", concepts},
                 {"withheld", withheld}});
    }
    return out;
}

Json objects_json(const LoadedCollection& collection) {
    Json out = Json::array();
    for (const LoadedObject& o : collection.objects) {
        std::set<std::string> concepts;
        if (o.error.empty())
            for (const Json& w : annotation_textures(o, nullptr))
                for (const Json& e : w.value("concepts", Json::array()))
                    concepts.insert(e.value("concept", std::string()));
        out.push_back(
            Json{{"id", o.id},
                 {"status", o.status},
                 // summary.csv's counts, also for an object whose files are damaged since
                 {"texels", o.texels >= 0 ? Json(o.texels) : Json(nullptr)},
                 {"textures", o.textures >= 0 ? Json(o.textures) : Json(nullptr)},
                 {"reason", o.reason},
                 {"error", o.error.empty() ? Json(nullptr) : Json(o.error)},
                 {"reannotate", o.error.empty() && o.reannotate},
                 {"concepts", Json(std::vector<std::string>(concepts.begin(), concepts.end()))}});
    }
    return out;
}

Json object_json(const LoadedObject& object, const Dictionary& dictionary) {
    if (!object.error.empty()) return Json{{"id", object.id}, {"error", object.error}};
    const Json& report = object.report;
    // The significance of each feature in each texture, from the report's words.
    std::map<int, Json> significance;
    for (const Json& w : annotation_textures(object, nullptr)) {
        Json s = Json::object();
        for (const Json& f : w.value("features", Json::array()))
            s[f.value("feature", std::string())] =
                f.contains("significance") ? f["significance"] : Json(nullptr);
        significance[w.value("texture", -1)] = s;
    }
    Json texels = Json::array();
    for (const Json& t : report["texels"]) {
        const int texture = t.value("texture", -1);
        Json features = Json::object(), sig = Json::object(), interval = Json::object();
        const Json& values = t.contains("features") ? t["features"] : Json::object();
        for (const char* id : kFeatureIds) {
            const Json v = values.contains(id) ? values[id] : Json(nullptr);
            features[id] = v;
            const auto s = significance.find(texture);
            sig[id] =
                s != significance.end() && s->second.contains(id) ? s->second[id] : Json(nullptr);
            const DictionaryConcept* c =
                v.is_number() ? dictionary.find(feature_column(id), v.get<double>()) : nullptr;
            interval[id] = c ? Json(c->id) : Json(nullptr);
        }
        texels.push_back(Json{{"id", t.value("id", -1)},
                              {"texture", texture},
                              {"features", features},
                              {"significance", sig},
                              {"interval", interval}});
    }
    return Json{{"id", object.id},
                {"error", nullptr},
                {"faces", report["mesh"].value("faces", 0)},
                {"vertices", report["mesh"].value("vertices", 0)},
                {"textures", textures_json(object, dictionary)},
                {"texels", texels}};
}

Json features_json(const LoadedCollection& collection) {
    Json out = Json::object();
    for (const char* id : kFeatureIds)
        out[id] = {{"texels", Json::array()}, {"textures", Json::array()}};
    for (const LoadedObject& o : collection.objects) {
        if (!o.error.empty()) continue;
        for (const Json& t : o.report["texels"]) {
            const Json& values = t.contains("features") ? t["features"] : Json::object();
            for (const char* id : kFeatureIds)
                out[id]["texels"].push_back(values.contains(id) ? values[id] : Json(nullptr));
        }
        for (const Json& w : annotation_textures(o, nullptr))
            for (const Json& f : w.value("features", Json::array())) {
                const std::string id = f.value("feature", std::string());
                if (out.contains(id))
                    out[id]["textures"].push_back(f.contains("value") ? f["value"] : Json(nullptr));
            }
    }
    return out;
}

std::vector<double> texel_depths(const Json& report) {
    std::vector<double> depth;
    if (!report.is_object() || !report.contains("texels")) return depth;
    for (const Json& t : report["texels"])
        depth.push_back(t.contains("features") && t["features"].contains("depth_mean")
                            ? number(t["features"]["depth_mean"])
                            : std::numeric_limits<double>::quiet_NaN());
    return depth;
}

}  // namespace geotex::view
