#include "cli/collection.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <map>
#include <system_error>

#include "annotation/digest.hpp"
#include "cli/dictionary_input.hpp"
#include "cli/output.hpp"
#include "common/detail/csv.hpp"
#include "common/detail/text.hpp"
#include "ontology/rdf_lexical.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::cli {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string trim(const std::string& s) {
    std::size_t a = 0, b = s.size();
    while (a < b && detail::is_space(s[a])) ++a;
    while (b > a && detail::is_space(s[b - 1])) --b;
    return s.substr(a, b - a);
}

// A message quoting a cell keeps to one line: control bytes (a CR or LF inside a quoted
// cell) are written as \xNN; the rest, UTF-8 included, is left as it is.
std::string controls_escaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u != 0x7f) {
            out += c;
            continue;
        }
        static const char hex[] = "0123456789abcdef";
        out += "\\x";
        out += hex[u >> 4];
        out += hex[u & 15];
    }
    return out;
}

std::string stem_of(const std::string& file_name) {
    const auto slash = file_name.find_last_of('/');
    std::string name = slash == std::string::npos ? file_name : file_name.substr(slash + 1);
    const auto dot = name.find_last_of('.');
    return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

Collection read_directory(const std::string& dir) {
    Collection c;
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) throw CliError(kExitInput, dir + ": cannot list the directory (" + ec.message() + ")");
    for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec)
            throw CliError(kExitInput, dir + ": cannot list the directory (" + ec.message() + ")");
        const std::string name = it->path().filename().string();
        // Hidden files are skipped: among them the temporaries of interrupted writes.
        if (name.empty() || name[0] == '.' || !is_mesh_file_name(name)) continue;
        std::error_code type_ec;
        if (!fs::is_regular_file(it->path(), type_ec)) continue;
        CollectionObject o;
        o.mesh = name;
        o.path = (fs::path(dir) / name).string();
        o.where = o.path;
        o.id = stem_of(name);
        c.objects.push_back(std::move(o));
    }
    return c;
}

Collection manifest_rows(const std::string& text, const std::string& file) {
    std::vector<detail::CsvRow> rows;
    try {
        rows = detail::parse_csv(text, file);
    } catch (const Error& e) {
        throw CliError(kExitInput, e.located(file));
    }
    if (rows.empty())
        throw CliError(kExitInput,
                       file + ": empty manifest (a header row with a 'mesh' column is needed)");
    Collection c;
    const auto& header = rows.front().fields;
    int mesh_col = -1, id_col = -1, object_col = -1, unit_col = -1;
    std::vector<std::string> ignored;
    for (std::size_t k = 0; k < header.size(); ++k) {
        const std::string name = lower(trim(header[k]));
        if (name == "mesh" && mesh_col < 0)
            mesh_col = static_cast<int>(k);
        else if (name == "id" && id_col < 0)
            id_col = static_cast<int>(k);
        else if (name == "object" && object_col < 0)
            object_col = static_cast<int>(k);
        else if (name == "mesh_unit" && unit_col < 0)
            unit_col = static_cast<int>(k);
        else
            ignored.push_back(detail::printable(header[k]));
    }
    if (mesh_col < 0)
        throw CliError(kExitInput, file + ":" + std::to_string(rows.front().line) +
                                       ": the header has no 'mesh' column (columns: mesh, and "
                                       "optionally id, object, mesh_unit)");
    if (!ignored.empty()) {
        std::string list;
        for (const auto& n : ignored) list += (list.empty() ? "'" : ", '") + n + "'";
        c.notes.push_back(file + ": columns ignored: " + list);
    }
    const fs::path base = fs::path(file).parent_path();
    for (std::size_t r = 1; r < rows.size(); ++r) {
        const auto& row = rows[r];
        CollectionObject o;
        o.where = file + ":" + std::to_string(row.line);
        if (row.fields.size() != header.size()) {
            o.id = row.fields.size() > static_cast<std::size_t>(std::max(mesh_col, id_col))
                       ? (id_col >= 0 ? row.fields[static_cast<std::size_t>(id_col)]
                                      : stem_of(row.fields[static_cast<std::size_t>(mesh_col)]))
                       : row.fields.front();
            if (static_cast<std::size_t>(mesh_col) < row.fields.size())
                o.mesh = trim(row.fields[static_cast<std::size_t>(mesh_col)]);
            o.error = o.where + ": " + std::to_string(row.fields.size()) +
                      " fields, the header has " + std::to_string(header.size());
            c.objects.push_back(std::move(o));
            continue;
        }
        o.mesh = trim(row.fields[static_cast<std::size_t>(mesh_col)]);
        o.id = id_col >= 0 ? trim(row.fields[static_cast<std::size_t>(id_col)]) : stem_of(o.mesh);
        if (object_col >= 0) o.object_iri = trim(row.fields[static_cast<std::size_t>(object_col)]);
        if (unit_col >= 0) o.mesh_unit = trim(row.fields[static_cast<std::size_t>(unit_col)]);
        if (!o.object_iri.empty()) {
            try {
                validate_iri(o.object_iri, "object IRI");
            } catch (const InvalidInput& e) {
                o.error = o.where + ": column 'object': " + controls_escaped(e.what());
            }
        }
        if (!o.mesh_unit.empty() && !parse_mesh_unit(o.mesh_unit))
            o.error = o.where + ": column 'mesh_unit': '" + detail::printable(o.mesh_unit) +
                      "' is not a unit: mm, cm, m or in";
        if (o.mesh.empty()) {
            o.error = o.where + ": empty 'mesh' cell";
        } else if (o.error.empty()) {
            const fs::path p(o.mesh);
            o.path = p.is_absolute() || base.empty() ? o.mesh : (base / p).string();
        }
        c.objects.push_back(std::move(o));
    }
    return c;
}

}  // namespace

bool is_mesh_file_name(const std::string& name) {
    const auto dot = name.find_last_of('.');
    if (dot == std::string::npos) return false;
    const std::string ext = lower(name.substr(dot));
    return ext == ".ply" || ext == ".off" || ext == ".obj" || ext == ".stl";
}

std::string check_object_id(const std::string& id) {
    if (id.empty()) return "empty object id";
    if (id.size() > 200) return "object id longer than 200 bytes";
    if (id[0] == '.') return "object id '" + detail::printable(id) + "' starts with '.'";
    for (std::size_t i = 0; i < id.size();) {
        char32_t cp = 0;
        const std::size_t n = detail::utf8_decode(id, i, cp);
        if (n == 0) return "object id '" + detail::printable(id) + "' is not valid UTF-8";
        if (cp < 0x20 || cp == 0x7f || (cp >= 0x80 && cp < 0xa0))
            return "object id '" + detail::printable(id) + "' holds a control character";
        if (cp == '/' || cp == '\\')
            return "object id '" + detail::printable(id) + "' holds a '/' or '\\'";
        i += n;
    }
    return {};
}

namespace {

// Ids checked, shared ids failed, objects sorted: the same for a directory and a manifest.
void finish_collection(Collection& c) {
    for (auto& o : c.objects)
        if (o.error.empty()) {
            const std::string why = check_object_id(o.id);
            if (!why.empty()) o.error = o.where + ": " + why;
        }
    // Every object that shares its id fails: which one was meant cannot be guessed.
    std::map<std::string, std::vector<std::size_t>> by_id;
    for (std::size_t i = 0; i < c.objects.size(); ++i)
        if (c.objects[i].error.empty()) by_id[c.objects[i].id].push_back(i);
    for (const auto& [id, members] : by_id) {
        if (members.size() < 2) continue;
        for (std::size_t i : members) {
            std::string others;
            for (std::size_t j : members)
                if (j != i) others += (others.empty() ? "" : ", ") + c.objects[j].where;
            c.objects[i].error = c.objects[i].where + ": duplicate object id '" +
                                 detail::printable(id) + "' (also " + others + ")";
        }
    }
    std::sort(c.objects.begin(), c.objects.end(),
              [](const CollectionObject& a, const CollectionObject& b) {
                  return a.id != b.id ? a.id < b.id : a.where < b.where;
              });
}

}  // namespace

Collection parse_manifest(const std::string& text, const std::string& file) {
    Collection c = manifest_rows(text, file);
    finish_collection(c);
    return c;
}

Collection read_collection(const std::string& input) {
    std::error_code ec;
    const auto status = fs::status(input, ec);
    if (ec || !fs::exists(status))
        throw CliError(kExitInput, input + ": no such file or directory");
    if (!fs::is_directory(status)) {
        if (is_mesh_file_name(input))
            throw CliError(kExitUsage,
                           input +
                               ": a mesh, not a collection: give its directory or a CSV manifest "
                               "(or use 'geotex annotate' for one mesh)");
        return parse_manifest(read_text_file(input), input);
    }
    Collection c = read_directory(input);
    finish_collection(c);
    return c;
}

int shard_of(const std::string& id, int num_shards) {
    const std::string hex = sha256_hex(id);
    std::uint64_t v = 0;
    for (int i = 0; i < 16; ++i) {
        const char ch = hex[static_cast<std::size_t>(i)];
        v = (v << 4) | static_cast<std::uint64_t>(ch <= '9' ? ch - '0' : ch - 'a' + 10);
    }
    return static_cast<int>(v % static_cast<std::uint64_t>(num_shards)) + 1;
}

std::string expand_iri_template(const std::string& option, const std::string& templ,
                                const std::string& id, const std::string& sha256) {
    std::string out;
    bool named = false;
    for (std::size_t i = 0; i < templ.size();) {
        if (templ[i] != '{') {
            out += templ[i++];
            continue;
        }
        const auto close = templ.find('}', i);
        const std::string name =
            close == std::string::npos ? templ.substr(i) : templ.substr(i, close - i + 1);
        if (name == "{id}")
            out += rdf_detail::iri_segment(id);
        else if (name == "{sha256}")
            out += sha256;
        else
            throw CliError(kExitUsage, option + ": unknown placeholder '" +
                                           detail::printable(name) + "' (known: {id}, {sha256})");
        named = true;
        i += name.size();
    }
    if (!named)
        throw CliError(
            kExitUsage,
            option + ": '" + detail::printable(templ) +
                "' names neither {id} nor {sha256}, so every object would share its IRIs");
    return out;
}

}  // namespace geotex::cli
