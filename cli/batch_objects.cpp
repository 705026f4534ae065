#include "cli/batch_objects.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "annotation/digest.hpp"
#include "cli/output.hpp"
#include "common/errors.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::cli {

namespace fs = std::filesystem;

namespace {

constexpr int kRunSchema = 1;

/// Empty when `path` is a regular file and no symbolic link, else why not. Inside OUTDIR
/// geotex reads only what it wrote: a planted link could make publish send another user's
/// file to the store, and a FIFO would block.
std::string not_plain(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return std::strerror(errno);
    if (S_ISLNK(st.st_mode)) return "is a symbolic link, not followed inside an output directory";
    if (S_ISDIR(st.st_mode)) return "is a directory";
    if (!S_ISREG(st.st_mode)) return "is not a regular file";
    return {};
}

/// The bytes of a file; nullopt with `reason` when it cannot be read.
std::optional<std::string> read_bytes(const std::string& path, std::string& reason) {
    reason = not_plain(path);
    if (!reason.empty()) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        reason = std::strerror(errno);
        return std::nullopt;
    }
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) {
        reason = "read failed";
        return std::nullopt;
    }
    return bytes;
}

bool is_sha256(const std::string& s) {
    return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

/// A run.json, checked.
struct Stamp {
    BatchObject object;
    std::vector<std::string> outputs;  ///< the file names it lists
};

/// The stamp of `id`, checked; throws CliError (input) naming run.json.
Stamp read_stamp(const std::string& dir, const std::string& id) {
    const std::string path = dir + "/run.json";
    const auto fail = [&](const std::string& what) {
        throw CliError(kExitInput, path + ": " + what);
    };
    std::string reason;
    const std::optional<std::string> text = read_bytes(path, reason);
    if (!text) fail("cannot read (" + reason + ")");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(*text);
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte is 1-based; messages of nlohmann name the place already.
        fail(std::string("not valid JSON: ") + e.what());
    }
    const auto string_at = [&](const nlohmann::json& object, const char* key,
                               const std::string& where) -> std::string {
        const auto it = object.find(key);
        if (it == object.end() || !it->is_string())
            fail("\"" + where + "\" is missing or not a string");
        return it->get<std::string>();
    };
    if (!j.is_object()) fail("not a JSON object; expected a geotex batch-object stamp");
    const auto stamp = j.find("geotex");
    if (stamp == j.end() || !stamp->is_object())
        fail("no \"geotex\" member: not a stamp written by geotex batch");
    if (string_at(*stamp, "document", "geotex.document") != "batch-object")
        fail("\"geotex.document\" is not \"batch-object\"");
    const auto schema = stamp->find("schema");
    if (schema == stamp->end() || !schema->is_number_integer())
        fail("\"geotex.schema\" is missing or not an integer");
    if (schema->get<long long>() != kRunSchema)
        fail("stamp schema " + std::to_string(schema->get<long long>()) +
             "; this geotex reads schema " + std::to_string(kRunSchema) +
             (schema->get<long long>() > kRunSchema ? " (written by a newer geotex?)" : ""));
    const std::string stamped_id = string_at(j, "id", "id");
    if (stamped_id != id)
        fail("\"id\" is '" + stamped_id.substr(0, 200) + "' but the directory is '" + id + "'");
    Stamp result;
    BatchObject& object = result.object;
    object.id = id;
    object.dir = dir;
    object.graph = string_at(j, "graph", "graph");
    try {
        validate_iri(object.graph, "graph IRI");
    } catch (const Error& e) {
        fail(std::string("\"graph\": ") + e.what());
    }
    const auto outputs = j.find("outputs");
    if (outputs == j.end() || !outputs->is_object())
        fail("\"outputs\" is missing or not an object");
    object.annotation_sha256 = string_at(*outputs, "annotation.ttl", "outputs.annotation.ttl");
    if (!is_sha256(object.annotation_sha256))
        fail("\"outputs\": the digest of annotation.ttl is not 64 lower-case hexadecimal digits");
    for (const auto& [name, digest] : outputs->items()) {
        if (!digest.is_string() || !is_sha256(digest.get<std::string>()))
            fail("\"outputs\": the digest of '" + name +
                 "' is not 64 lower-case hexadecimal digits");
        if (name.empty() || name.find('/') != std::string::npos || name[0] == '.')
            fail("\"outputs\": '" + name + "' is not a file name of the object's directory");
        result.outputs.push_back(name);
    }
    object.annotation_path = dir + "/annotation.ttl";
    return result;
}

}  // namespace

BatchObjects list_batch_objects(const std::string& outdir) {
    std::error_code ec;
    if (!fs::exists(outdir, ec)) throw CliError(kExitInput, outdir + ": no such directory");
    if (!fs::is_directory(outdir, ec)) throw CliError(kExitInput, outdir + ": not a directory");
    const std::string objects_dir = outdir + "/objects";
    if (!fs::is_directory(objects_dir, ec))
        throw CliError(kExitInput, outdir +
                                       ": not a geotex batch directory (no objects/ in it; see "
                                       "docs/collections.md)");
    std::vector<std::string> ids;
    fs::directory_iterator it(objects_dir, ec);
    if (ec) throw CliError(kExitInput, objects_dir + ": cannot list (" + ec.message() + ")");
    for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec) throw CliError(kExitInput, objects_dir + ": cannot list (" + ec.message() + ")");
        const std::string name = it->path().filename().string();
        // Object ids never start with '.': such entries are temporary files of a batch run.
        if (name.empty() || name[0] == '.') continue;
        std::error_code type_ec;
        if (it->is_directory(type_ec)) ids.push_back(name);  // a link to one too: reported below
    }
    std::sort(ids.begin(), ids.end());

    BatchObjects result;
    for (const std::string& id : ids) {
        const std::string dir = objects_dir + "/" + id;
        struct stat st {};
        if (::lstat(dir.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
            result.incomplete.push_back(
                {id,
                 "objects/" + id + " is a symbolic link, not followed inside an output directory"});
            continue;
        }
        if (!fs::exists(dir + "/run.json", ec)) {
            result.incomplete.push_back({id, "no run.json (not finished)"});
            continue;
        }
        if (const std::string why = not_plain(dir + "/run.json"); !why.empty()) {
            result.incomplete.push_back({id, "run.json " + why});
            continue;
        }
        Stamp stamp = read_stamp(dir, id);
        std::string missing, why;
        for (const std::string& name : stamp.outputs) {
            why = not_plain(dir + "/" + name);
            if (!why.empty()) {
                missing = name;
                break;
            }
        }
        BatchObject& object = stamp.object;
        if (!missing.empty()) {
            result.incomplete.push_back(
                {id, "run.json lists '" + missing + "', which " +
                         (why == std::strerror(ENOENT) ? std::string("is missing") : why)});
            continue;
        }
        std::string reason;
        if (!read_verified_annotation(object, reason)) {
            result.incomplete.push_back({id, reason});
            continue;
        }
        result.complete.push_back(std::move(object));
    }
    return result;
}

std::optional<std::string> read_verified_annotation(const BatchObject& object,
                                                    std::string& reason) {
    std::string why;
    std::optional<std::string> text = read_bytes(object.annotation_path, why);
    if (!text) {
        reason = "annotation.ttl cannot be read (" + why + ")";
        return std::nullopt;
    }
    if (sha256_hex(*text) != object.annotation_sha256) {
        reason = "annotation.ttl does not have the SHA-256 recorded in run.json";
        return std::nullopt;
    }
    return text;
}

}  // namespace geotex::cli
