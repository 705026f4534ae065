#include "view/collection.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>

#include "common/detail/csv.hpp"
#include "common/errors.hpp"
#include "view/security.hpp"

namespace geotex::view {

namespace fs = std::filesystem;

namespace {

// A file descriptor closed on every path out.
class Fd {
  public:
    explicit Fd(int fd) : fd_(fd) {}
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    ~Fd() {
        if (fd_ >= 0) ::close(fd_);
    }
    int get() const { return fd_; }
    int release() {
        const int fd = fd_;
        fd_ = -1;
        return fd;
    }

  private:
    int fd_;
};

[[noreturn]] void io_failure(const std::string& what, const std::string& where) {
    throw IoError(what + ": " + std::strerror(errno), where);
}

// The regular file `name` under the directory `dir`, opened without following a link; `where`
// names it in messages.
int open_file_at(int dir, const std::string& name, const std::string& where) {
    Fd fd(::openat(dir, name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK));
    if (fd.get() < 0) {
        if (errno == ELOOP) throw IoError("is a symbolic link; geotex view never follows one", where);
        if (errno == ENOENT) throw IoError("missing", where);
        io_failure("cannot open", where);
    }
    struct stat st {};
    if (::fstat(fd.get(), &st) != 0) io_failure("cannot read", where);
    if (!S_ISREG(st.st_mode)) throw IoError("is not a regular file", where);
    return fd.release();
}

std::string read_fd(int fd, const std::string& where) {
    struct stat st {};
    if (::fstat(fd, &st) != 0) io_failure("cannot read", where);
    std::string bytes(static_cast<std::size_t>(st.st_size), '\0');
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) io_failure("cannot read", where);
        if (n == 0) break;  // shrank while read: what is there
        done += static_cast<std::size_t>(n);
    }
    bytes.resize(done);
    return bytes;
}

std::string read_at(int dir, const std::string& name, const std::string& where) {
    const Fd fd(open_file_at(dir, name, where));
    return read_fd(fd.get(), where);
}

// A directory under `dir`, opened without following a link.
int open_dir_at(int dir, const std::string& name, const std::string& where) {
    const int fd = ::openat(dir, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ELOOP || errno == ENOTDIR)
            throw IoError("is not a directory (a symbolic link is never followed)", where);
        if (errno == ENOENT) throw IoError("missing", where);
        io_failure("cannot open", where);
    }
    return fd;
}

bool is_regular(const fs::path& p) {
    struct stat st {};
    return ::lstat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

int parse_count(const std::string& cell) {
    if (cell.empty() || cell.size() > 9) return -1;
    for (char c : cell)
        if (c < '0' || c > '9') return -1;
    return std::stoi(cell);
}

// The rows of one summary CSV (header id,mesh,status,seconds,texels,textures,reason, by name).
void read_summary(const std::string& text, const std::string& file,
                  std::map<std::string, ViewObject>& objects) {
    const std::vector<detail::CsvRow> rows = detail::parse_csv(text, file);
    if (rows.empty()) throw ParseError("empty summary (no header)", file, 1);
    std::map<std::string, std::size_t> column;
    for (std::size_t k = 0; k < rows[0].fields.size(); ++k) column[rows[0].fields[k]] = k;
    if (!column.count("id") || !column.count("status"))
        throw ParseError("no 'id' or 'status' column: not a geotex batch summary", file, 1);
    auto cell = [&](const detail::CsvRow& row, const char* name) {
        const auto it = column.find(name);
        return it != column.end() && it->second < row.fields.size() ? row.fields[it->second]
                                                                    : std::string();
    };
    for (std::size_t r = 1; r < rows.size(); ++r) {
        ViewObject o;
        o.id = cell(rows[r], "id");
        o.status = cell(rows[r], "status");
        o.texels = parse_count(cell(rows[r], "texels"));
        o.textures = parse_count(cell(rows[r], "textures"));
        o.reason = cell(rows[r], "reason");
        // The same object in two shards' summaries: the first read (summary.csv) stays.
        objects.emplace(o.id, std::move(o));
    }
}

// The report's texels keep everything but their face lists, which only the mesh needs and
// which are most of a large report's bytes.
void load_report(const ViewCollection& c, ViewObject& o) {
    const std::string text = read_object_file(c, o, ObjectFile::Report);
    nlohmann::json report = nlohmann::json::parse(text, nullptr, false);
    const std::string where = c.single ? "report.json" : "objects/" + o.id + "/report.json";
    if (report.is_discarded()) throw ParseError("not JSON", where);
    if (!report.is_object() || !report.contains("texels") || !report["texels"].is_array() ||
        !report.contains("textures") || !report["textures"].is_array() ||
        !report.contains("mesh") || !report["mesh"].is_object())
        throw ParseError("not a geotex report (no texels, textures or mesh)", where);
    for (auto& t : report["texels"])
        if (t.is_object()) t.erase("faces");
    if (o.texels < 0) o.texels = static_cast<int>(report["texels"].size());
    if (o.textures < 0) o.textures = static_cast<int>(report["textures"].size());
    o.report = std::move(report);
}

}  // namespace

const char* file_name(ObjectFile file) {
    switch (file) {
        case ObjectFile::Report: return "report.json";
        case ObjectFile::Segmentation: return "segmentation.ply";
        case ObjectFile::Geometry: return "geometry.cbor";
        case ObjectFile::Run: return "run.json";
    }
    return "";
}

const ViewObject* ViewCollection::find(const std::string& id) const {
    if (!object_id_problem(id).empty()) return nullptr;
    const auto it = std::lower_bound(objects.begin(), objects.end(), id,
                                     [](const ViewObject& o, const std::string& k) { return o.id < k; });
    return it != objects.end() && it->id == id ? &*it : nullptr;
}

namespace {

// The file of an object, open, with every check of read_object_file made; `where` receives
// its name relative to PATH.
int open_object_file(const ViewCollection& collection, const ViewObject& object, ObjectFile file,
                     std::string& where) {
    where = file_name(file);
    if (!object_id_problem(object.id).empty())
        throw IoError("not an object id: " + object_id_problem(object.id), object.id);
    const Fd root(::open(collection.root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (root.get() < 0) io_failure("cannot open", collection.root);
    if (collection.single) return open_file_at(root.get(), file_name(file), where);
    const Fd objects(open_dir_at(root.get(), "objects", "objects"));
    const std::string dir = "objects/" + object.id;
    const Fd object_dir(open_dir_at(objects.get(), object.id, dir));
    where = dir + "/" + file_name(file);
    return open_file_at(object_dir.get(), file_name(file), where);
}

}  // namespace

std::string read_object_file(const ViewCollection& collection, const ViewObject& object,
                             ObjectFile file) {
    std::string where;
    const Fd fd(open_object_file(collection, object, file, where));
    return read_fd(fd.get(), where);
}

bool has_object_file(const ViewCollection& collection, const ViewObject& object, ObjectFile file) {
    try {
        std::string where;
        const Fd fd(open_object_file(collection, object, file, where));
        return true;
    } catch (const Error&) {
        return false;
    }
}

ViewCollection load_view_collection(const std::string& path) {
    std::error_code ec;
    const fs::path root = fs::canonical(path, ec);
    if (ec) throw InvalidInput(std::string("cannot open: ") + ec.message(), path);
    if (!fs::is_directory(root, ec))
        throw InvalidInput("not a directory; give a geotex batch output directory or a directory "
                           "holding one object's report.json and segmentation.ply",
                           path);
    ViewCollection c;
    c.root = root.string();
    c.name = root.filename().string();
    std::vector<std::string> summaries;
    if (is_regular(root / "summary.csv")) summaries.push_back("summary.csv");
    std::vector<std::string> shards;
    for (const auto& entry : fs::directory_iterator(root, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("summary-shard-", 0) == 0 && name.size() > 4 &&
            name.compare(name.size() - 4, 4, ".csv") == 0 && is_regular(entry.path()))
            shards.push_back(name);
    }
    std::sort(shards.begin(), shards.end());
    summaries.insert(summaries.end(), shards.begin(), shards.end());

    if (summaries.empty()) {
        if (!is_regular(root / "report.json") || !is_regular(root / "segmentation.ply"))
            throw InvalidInput(
                "neither a geotex batch output directory (no summary.csv) nor one object's "
                "outputs (no report.json and segmentation.ply)",
                path);
        c.single = true;
        ViewObject o;
        o.id = c.name;
        o.status = "ok";
        c.objects.push_back(std::move(o));
    } else {
        std::map<std::string, ViewObject> rows;
        const Fd dir(::open(c.root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
        if (dir.get() < 0) io_failure("cannot open", path);
        for (const std::string& s : summaries) read_summary(read_at(dir.get(), s, s), s, rows);
        for (auto& [id, o] : rows) c.objects.push_back(std::move(o));
    }
    for (ViewObject& o : c.objects) {
        if (const std::string why = object_id_problem(o.id); !why.empty()) {
            o.error = "the id " + why + "; geotex view does not read its files";
            continue;
        }
        try {
            load_report(c, o);
            // The mesh is read when it is asked for (a corrupt one answers with its error
            // then); here only that it is there.
            std::string where;
            const Fd seg(open_object_file(c, o, ObjectFile::Segmentation, where));
            o.has_geometry = has_object_file(c, o, ObjectFile::Geometry);
        } catch (const Error& e) {
            o.error = e.located();
            if (o.status == "failed" && !o.reason.empty()) o.error = "batch failed: " + o.reason;
            o.report = nullptr;
        }
    }
    return c;
}

}  // namespace geotex::view
