#include "pipeline/loaded_collection.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include "annotation/digest.hpp"
#include "common/detail/csv.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"

namespace geotex {

namespace {

namespace fs = std::filesystem;

/// Closes a file descriptor when it goes out of scope.
struct Fd {
    int fd = -1;
    explicit Fd(int f) : fd(f) {}
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

std::string join_path(const std::string& root, const std::string& id, const std::string& name) {
    return (fs::path(root) / id / name).string();
}

/// The reason of a failed open, as messages say it: a link is named as such (O_NOFOLLOW
/// gives ELOOP, or ENOTDIR for a directory opened with O_DIRECTORY through a link).
std::string open_failure(int error) {
    if (error == ELOOP) return "is a symbolic link; refused (geotex reads no file through a link)";
    return std::string("cannot open (") + std::strerror(error) + ")";
}

/// The regular file `name` in the directory `dirfd`, opened without following a link; `path`
/// names it in messages.
std::string read_regular_file_at(int dirfd, const std::string& name, const std::string& path) {
    // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it
    const Fd fd(::openat(dirfd, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
    if (fd.fd < 0) throw IoError(open_failure(errno), path);
    struct stat st {};
    if (::fstat(fd.fd, &st) != 0) throw IoError(open_failure(errno), path);
    if (!S_ISREG(st.st_mode)) throw IoError("not a regular file; refused", path);
    std::string bytes;
    bytes.reserve(static_cast<size_t>(st.st_size));
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd.fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw IoError(std::string("read failed (") + std::strerror(errno) + ")", path);
        if (n == 0) break;
        bytes.append(buffer, static_cast<size_t>(n));
    }
    return bytes;
}

/// The entries of a summary CSV: id -> (status, texels, textures, reason).
struct SummaryRow {
    std::string id, status, reason;
    long texels = -1, textures = -1;
};

/// A count of summary.csv; -1 when the cell is empty (a failed object) or not a count.
long number_field(const std::string& s) {
    long value = -1;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    return ec == std::errc() && end == s.data() + s.size() && value >= 0 ? value : -1;
}

std::vector<SummaryRow> read_summary(const std::string& file, const std::string& text) {
    const auto rows = detail::parse_csv(text, file);
    if (rows.empty()) throw ParseError("empty summary: expected the header row", file, 1, 1);
    std::map<std::string, size_t> column;
    for (size_t i = 0; i < rows[0].fields.size(); ++i) column.emplace(rows[0].fields[i], i);
    for (const char* required : {"id", "status"})
        if (!column.count(required))
            throw ParseError(std::string("no column '") + required +
                                 "' in the header (a geotex batch summary has id,mesh,status,"
                                 "seconds,texels,textures,reason)",
                             file, rows[0].line, 1);
    const auto field = [&](const detail::CsvRow& row, const char* name) {
        const auto it = column.find(name);
        return it != column.end() && it->second < row.fields.size() ? row.fields[it->second]
                                                                    : std::string();
    };
    std::vector<SummaryRow> out;
    for (size_t r = 1; r < rows.size(); ++r) {
        SummaryRow s;
        s.id = field(rows[r], "id");
        s.status = field(rows[r], "status");
        s.reason = field(rows[r], "reason");
        s.texels = number_field(field(rows[r], "texels"));
        s.textures = number_field(field(rows[r], "textures"));
        out.push_back(std::move(s));
    }
    return out;
}

/// A regular file directly in `dir`, read without following a link; throws as
/// read_object_file does.
std::string read_plain_file(const std::string& dir, const std::string& name) {
    const std::string path = (fs::path(dir) / name).string();
    const Fd dfd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (dfd.fd < 0) throw IoError(open_failure(errno), dir);
    return read_regular_file_at(dfd.fd, name, path);
}

DescriptionParams params_from(const nlohmann::json& choice) {
    DescriptionParams p;
    p.max_concepts = choice.at("max_concepts").get<int>();
    p.max_significance = choice.at("max_significance").get<double>();
    p.min_agreement = choice.at("min_agreement").get<double>();
    p.min_stability = choice.at("min_stability").get<double>();
    p.num_resamples = choice.at("resamples").get<int>();
    return p;
}

ObjectWords words_from(const nlohmann::json& textures) {
    ObjectWords words;
    for (const auto& t : textures) {
        TextureWords w;
        for (const auto& c : t.at("concepts")) w.push_back(c.at("concept").get<std::string>());
        words.push_back(std::move(w));
    }
    return words;
}

/// The digest run.json records for `name`, or "".
std::string recorded_digest(const nlohmann::json& run, const std::string& name) {
    if (!run.is_object() || !run.contains("outputs") || !run["outputs"].is_object() ||
        !run["outputs"].contains(name) || !run["outputs"][name].is_string())
        return "";
    return run["outputs"][name].get<std::string>();
}

/// Fills `o` from its files; an exception's message becomes its error.
void load_object(const std::string& root, bool stamped_only, LoadedObject& o) {
    const std::string run_path = join_path(root, o.id, "run.json");
    nlohmann::json run;
    bool have_run = false;
    try {
        run = nlohmann::json::parse(read_object_file(root, o.id, "run.json"));
        have_run = true;
    } catch (const nlohmann::json::exception& e) {
        throw IoError(std::string("not JSON (") + e.what() + ")", run_path);
    } catch (const IoError&) {
        // a batch object is complete only when stamped (docs/collections.md)
        if (stamped_only) throw;
    }
    const std::string report_path = join_path(root, o.id, "report.json");
    const std::string report_text = read_object_file(root, o.id, "report.json");
    const std::string report_digest = recorded_digest(run, "report.json");
    if (have_run && report_digest != sha256_hex(report_text))
        throw IoError("changed since its run (its digest is not the one run.json records)",
                      report_path);
    try {
        o.report = nlohmann::json::parse(report_text);
        const auto& a = o.report.at("annotation");
        o.params = params_from(a.at("choice"));
        o.words = words_from(a.at("textures"));
        o.dictionary_sha256 = a.at("dictionary").at("sha256").get<std::string>();
        if (!o.report.at("texels").is_array()) throw IoError("texels is not a list", report_path);
    } catch (const nlohmann::json::exception& e) {
        throw IoError(std::string("not a geotex annotation report (") + e.what() + ")",
                      report_path);
    }
    const size_t num_texels = o.report["texels"].size();
    if (o.texels < 0 && o.textures < 0) {  // one object's directory: no summary
        o.texels = static_cast<long>(num_texels);
        o.textures = static_cast<long>(o.words.size());
    }

    const std::string cache_path = join_path(root, o.id, "geometry.cbor");
    std::string cache;
    try {
        cache = read_object_file(root, o.id, "geometry.cbor");
    } catch (const IoError&) {
        // without the file the words are shown, not chosen again (view/README.md); a link
        // or another kind of file in its place is an error
        struct stat st {};
        if (::lstat(cache_path.c_str(), &st) != 0 && errno == ENOENT) return;
        throw;
    }
    const std::string cache_digest = recorded_digest(run, "geometry.cbor");
    if (have_run && cache_digest != sha256_hex(cache))
        throw IoError("changed since its run (its digest is not the one run.json records)",
                      cache_path);
    try {
        o.geometry = read_geometry_tables(cache);
    } catch (const InvalidInput& e) {
        throw IoError(e.what(), cache_path);
    }
    if (static_cast<size_t>(o.geometry.features.rows()) != num_texels ||
        static_cast<size_t>(o.geometry.num_textures) != o.words.size())
        throw IoError("holds " + std::to_string(o.geometry.features.rows()) + " texels and " +
                          std::to_string(o.geometry.num_textures) + " textures, report.json " +
                          std::to_string(num_texels) + " and " + std::to_string(o.words.size()),
                      cache_path);
    o.reannotate = true;
}

void load_each(LoadedCollection& c, bool stamped_only) {
    tbb::parallel_for(size_t(0), c.objects.size(), [&](size_t i) {
        LoadedObject& o = c.objects[i];
        if (!o.error.empty()) return;
        try {
            load_object(c.objects_root, stamped_only, o);
        } catch (const Error& e) {
            o.error = e.located();
            o.reannotate = false;
            o.geometry = {};
        }
    });
}

bool regular_file_in(const fs::path& dir, const char* name) {
    std::error_code ec;
    return fs::is_regular_file(fs::symlink_status(dir / name, ec));
}

}  // namespace

bool is_object_id(std::string_view id) {
    return !id.empty() && id.front() != '.' && id.find('/') == std::string_view::npos &&
           id.find('\0') == std::string_view::npos;
}

std::string read_object_file(const std::string& root, const std::string& id,
                             const std::string& name) {
    const std::string path = join_path(root, id, name);
    if (!is_object_id(id))
        throw InvalidInput("refused object id '" + id +
                           "' (empty, with '/', or starting with '.')");
    if (!is_object_id(name)) throw InvalidInput("refused file name '" + name + "'", path);
    // the root itself (OUTDIR/objects) may not be a link either: the files stay under PATH
    const Fd rfd(::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (rfd.fd < 0) {
        struct stat st {};
        throw IoError(
            open_failure(::lstat(root.c_str(), &st) == 0 && S_ISLNK(st.st_mode) ? ELOOP : errno),
            root);
    }
    const Fd dfd(::openat(rfd.fd, id.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (dfd.fd < 0) {
        const int error = errno;
        struct stat st {};
        // O_NOFOLLOW with O_DIRECTORY reports a link as ENOTDIR on some systems
        if (::fstatat(rfd.fd, id.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISLNK(st.st_mode))
            throw IoError(open_failure(ELOOP), (fs::path(root) / id).string());
        throw IoError(open_failure(error), (fs::path(root) / id).string());
    }
    return read_regular_file_at(dfd.fd, name, path);
}

LoadedCollection load_collection(const std::string& path) {
    LoadedCollection c;
    c.path = path;
    std::error_code ec;
    const fs::path dir(path);
    if (!fs::is_directory(dir, ec))
        throw InvalidInput(
            "not a directory: expected a geotex batch output (summary.csv, objects/) or one "
            "object's outputs (report.json, segmentation.ply)",
            path);
    // The summaries of a batch: summary.csv and the shards' summary-shard-I-of-N.csv
    std::vector<std::string> summaries;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        const bool summary =
            name == "summary.csv" || (name.rfind("summary-shard-", 0) == 0 && name.size() > 4 &&
                                      name.compare(name.size() - 4, 4, ".csv") == 0);
        if (summary) summaries.push_back(name);
    }
    std::sort(summaries.begin(), summaries.end());
    if (!summaries.empty()) {
        c.batch = true;
        c.objects_root = (dir / "objects").string();
        std::set<std::string> seen;
        for (const auto& name : summaries) {
            const std::string file = (dir / name).string();
            for (auto& row : read_summary(file, read_plain_file(dir.string(), name))) {
                if (!seen.insert(row.id).second) continue;
                LoadedObject o;
                o.id = row.id;
                o.status = row.status;
                o.reason = row.reason;
                o.texels = row.texels;
                o.textures = row.textures;
                if (!is_object_id(o.id))
                    o.error = file + ": refused object id '" + o.id + "'";
                else if (o.status != "ok" && o.status != "skipped")
                    o.error = o.status + (o.reason.empty() ? "" : ": " + o.reason);
                c.objects.push_back(std::move(o));
            }
        }
        std::sort(c.objects.begin(), c.objects.end(),
                  [](const LoadedObject& a, const LoadedObject& b) { return a.id < b.id; });
        load_each(c, true);
        return c;
    }
    if (regular_file_in(dir, "report.json") && regular_file_in(dir, "segmentation.ply")) {
        // PATH as the user named it may be a link: its real place is the object's directory
        fs::path named = fs::canonical(dir, ec);
        if (ec) throw InvalidInput("cannot resolve (" + ec.message() + ")", path);
        c.objects_root = named.parent_path().string();
        LoadedObject o;
        o.id = named.filename().string();
        if (!is_object_id(o.id))
            throw InvalidInput(
                "the directory's name '" + o.id + "' cannot be an object id (it starts with '.')",
                path);
        c.objects.push_back(std::move(o));
        load_each(c, false);
        return c;
    }
    throw InvalidInput(
        "neither a geotex batch output (no summary.csv) nor one object's outputs (no " +
            std::string(regular_file_in(dir, "report.json") ? "segmentation.ply" : "report.json") +
            ")",
        path);
}

ObjectWords chosen_words(const std::vector<TextureDescription>& descriptions) {
    ObjectWords out;
    for (const auto& d : descriptions) {
        TextureWords w;
        for (int i : d.chosen) w.push_back(d.features[static_cast<size_t>(i)].concept_ptr->id);
        out.push_back(std::move(w));
    }
    return out;
}

std::vector<ObjectWords> chosen_words(
    const std::vector<std::vector<TextureDescription>>& descriptions) {
    std::vector<ObjectWords> out;
    for (const auto& d : descriptions) out.push_back(chosen_words(d));
    return out;
}

std::vector<ObjectWords> report_words(const LoadedCollection& collection) {
    std::vector<ObjectWords> out;
    for (const auto& o : collection.objects) out.push_back(o.words);
    return out;
}

std::string report_label_language(const nlohmann::json& report, const Dictionary& dictionary) {
    std::map<std::string, const DictionaryConcept*> by_id;
    for (const auto& c : dictionary.concepts) by_id.emplace(c.id, &c);
    std::vector<std::pair<const DictionaryConcept*, std::string>> recorded;
    try {
        for (const auto& t : report.at("annotation").at("textures"))
            for (const auto& c : t.at("concepts")) {
                const auto it = by_id.find(c.at("concept").get<std::string>());
                if (it == by_id.end()) return "";
                recorded.emplace_back(it->second, c.at("label").get<std::string>());
            }
    } catch (const nlohmann::json::exception&) {
        return "";
    }
    if (recorded.empty()) return "";
    std::vector<std::string> candidates = dictionary.languages;
    for (const auto& [c, label] : recorded)
        for (const auto& [lang, text] : c->labels)
            if (std::find(candidates.begin(), candidates.end(), lang) == candidates.end())
                candidates.push_back(lang);
    for (const auto& lang : candidates) {
        bool all = true;
        for (const auto& [c, label] : recorded) {
            const auto it = c->labels.find(lang);
            all = all && it != c->labels.end() && it->second == label;
        }
        if (all) return lang;
    }
    return "";
}

std::vector<std::vector<TextureDescription>> reannotate(const LoadedCollection& collection,
                                                        const Dictionary& dictionary) {
    std::vector<std::vector<TextureDescription>> out(collection.objects.size());
    // each object's description depends on its own data only, so the order of the threads
    // cannot change a result
    tbb::parallel_for(size_t(0), collection.objects.size(), [&](size_t i) {
        const LoadedObject& o = collection.objects[i];
        if (!o.reannotate) return;
        out[i] = describe_textures(o.geometry.features, o.geometry.texel_texture,
                                   o.geometry.num_textures, o.geometry.texture_orientation,
                                   dictionary, o.params);
    });
    return out;
}

std::vector<WordChange> diff_words(const LoadedCollection& collection,
                                   const std::vector<ObjectWords>& before,
                                   const std::vector<ObjectWords>& after) {
    if (before.size() != collection.objects.size() || after.size() != collection.objects.size())
        throw InvalidInput("diff_words: " + std::to_string(before.size()) + " and " +
                           std::to_string(after.size()) + " word lists for " +
                           std::to_string(collection.objects.size()) + " objects");
    std::vector<WordChange> changes;
    static const TextureWords none;
    for (size_t i = 0; i < collection.objects.size(); ++i) {
        if (!collection.objects[i].reannotate) continue;
        const size_t n = std::max(before[i].size(), after[i].size());
        for (size_t t = 0; t < n; ++t) {
            const TextureWords& b = t < before[i].size() ? before[i][t] : none;
            const TextureWords& a = t < after[i].size() ? after[i][t] : none;
            TextureWords sb = b, sa = a;
            std::sort(sb.begin(), sb.end());
            std::sort(sa.begin(), sa.end());
            const bool on_both = t < before[i].size() && t < after[i].size();
            if (on_both && sb == sa) continue;
            changes.push_back({collection.objects[i].id, static_cast<int>(t), b, a});
        }
    }
    return changes;
}

std::vector<FitObject> fit_objects(const LoadedCollection& collection) {
    std::vector<FitObject> out;
    for (const auto& o : collection.objects) {
        if (!o.reannotate) continue;
        FitObject f;
        f.id = o.id;
        f.features = o.geometry.features;
        f.texel_texture = o.geometry.texel_texture;
        f.num_textures = o.geometry.num_textures;
        f.texture_orientation = o.geometry.texture_orientation;
        f.params = o.params;
        out.push_back(std::move(f));
    }
    return out;
}

}  // namespace geotex
