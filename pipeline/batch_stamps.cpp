#include "pipeline/batch_stamps.hpp"

#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "annotation/digest.hpp"
#include "common/errors.hpp"
#include "pipeline/annotate.hpp"
#include "pipeline/file_digest.hpp"
#include "pipeline/read_text_file.hpp"

namespace geotex {

namespace fs = std::filesystem;

std::string stamp_options_sha256(const std::string& options_text, const std::string& version) {
    std::string key = "geotex " + version + "\n" + options_text + "\noutputs=";
    for (const auto& out : kObjectOutputs) key += std::string(out.file) + ",";
    return sha256_hex(key);
}

bool is_plain_file(const fs::path& path) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::optional<StampCounts> up_to_date_stamp(const fs::path& dir, const StampKey& key) {
    if (!is_plain_file(dir / kStampFile)) return std::nullopt;
    std::ifstream in(dir / kStampFile, std::ios::binary);
    if (!in) return std::nullopt;
    try {
        const nlohmann::json stamp = nlohmann::json::parse(in);
        if (stamp.at("mesh_sha256") != key.mesh_sha256 ||
            stamp.at("dictionary_sha256") != key.dictionary_sha256 ||
            stamp.at("options_sha256") != key.options_sha256)
            return std::nullopt;
        const auto& outputs = stamp.at("outputs");
        for (const auto& out : kObjectOutputs) {
            if (!outputs.contains(out.file) || !is_plain_file(dir / out.file)) return std::nullopt;
            if (outputs.at(out.file) != file_sha256((dir / out.file).string())) return std::nullopt;
        }
        return StampCounts{stamp.at("texels").get<long>(), stamp.at("textures").get<long>()};
    } catch (const std::exception&) {
        return std::nullopt;  // unreadable or foreign: run the object again
    }
}

Stamp make_stamp(const fs::path& dir, const StampKey& key, const std::string& id,
                 const std::string& mesh, const std::string& graph_base) {
    nlohmann::ordered_json outputs;
    for (const auto& out : kObjectOutputs)
        outputs[out.file] = file_sha256((dir / out.file).string());
    const nlohmann::json report =
        nlohmann::json::parse(read_text_file((dir / "report.json").string()));
    const StampCounts counts{static_cast<long>(report.at("texels").size()),
                             static_cast<long>(report.at("textures").size())};
    // The object's named graph in a store: its base, else the mesh's hash name (the IRI of the
    // mesh in the annotation), so that publishing a new run replaces the object's old one.
    const std::string graph = graph_base.empty() ? ni_name(key.mesh_sha256) : graph_base;
    nlohmann::ordered_json stamp;
    stamp["geotex"] = {{"version", version()}, {"document", "batch-object"}, {"schema", 1}};
    stamp["id"] = id;
    stamp["mesh"] = mesh;
    stamp["mesh_sha256"] = key.mesh_sha256;
    stamp["dictionary_sha256"] = key.dictionary_sha256;
    stamp["options_sha256"] = key.options_sha256;
    stamp["base"] = graph_base;
    stamp["graph"] = graph;
    stamp["texels"] = counts.texels;
    stamp["textures"] = counts.textures;
    stamp["outputs"] = outputs;
    return {stamp.dump(2) + '\n', counts};
}

}  // namespace geotex
