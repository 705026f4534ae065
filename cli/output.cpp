#include "cli/output.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace geotex::cli {

namespace {

// Temporary files to remove if a signal ends the process. Fixed-size storage so the
// handler only touches memory that is always valid (unlink is async-signal-safe); a command
// writes a few files at once, and one that would write more is refused rather than leave a
// file the handler does not know of.
constexpr int kMaxPending = 16;
char g_pending[kMaxPending][4096];
std::atomic<int> g_pending_used[kMaxPending];

// Whether `path` is now in the list (false: no slot is free, or the name does not fit one).
bool register_pending(const std::string& path) {
    if (path.size() >= sizeof g_pending[0]) return false;
    for (int i = 0; i < kMaxPending; ++i) {
        int expected = 0;
        if (g_pending_used[i].compare_exchange_strong(expected, 2)) {  // 2: being written
            std::memcpy(g_pending[i], path.c_str(), path.size() + 1);
            g_pending_used[i] = 1;
            return true;
        }
    }
    return false;
}

void unregister_pending(const std::string& path) {
    for (int i = 0; i < kMaxPending; ++i)
        if (g_pending_used[i] == 1 && path == g_pending[i]) g_pending_used[i] = 0;
}

void unlink_pending() {
    for (int i = 0; i < kMaxPending; ++i)
        if (g_pending_used[i] == 1) ::unlink(g_pending[i]);
}

// A signal sent to the process is taken by whichever of its threads first runs with it
// unblocked: often the main thread, but as readily a TBB worker still spinning after a loop.
// The handler then runs beside the thread that writes the outputs, which could create its
// next temporary file after the handler removed those it knew of and before the process
// ended (seen under load). So a temporary file is created only inside a short section that
// keeps these signals off the creating thread, and the handler, before removing anything,
// raises g_signalled and waits until no thread is inside: a thread that enters afterwards sees
// the flag and creates nothing, and a file created inside is registered before the handler
// reads the list.
std::atomic<bool> g_signalled{false};
std::atomic<int> g_creating{0};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "the signal handler may only use lock-free atomics");

[[noreturn]] void wait_for_the_end() {
    for (;;) ::pause();
}

sigset_t stop_signals() {
    sigset_t set;
    sigemptyset(&set);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, sig);
    return set;
}

// What create_pending returns when `tmp` could not be registered, and so was not created.
constexpr int kUntracked = -2;

// Registers `tmp` and creates it (exclusively and not through a link, with `mode`); returns
// the descriptor, or -1 with errno set, or kUntracked. A thread that comes here after a signal
// waits for the process to end.
int create_pending(const std::string& tmp, mode_t mode) {
    const sigset_t stops = stop_signals();
    sigset_t before;
    ::pthread_sigmask(SIG_BLOCK, &stops, &before);
    ++g_creating;
    if (g_signalled.load()) {
        --g_creating;
        ::pthread_sigmask(SIG_SETMASK, &before, nullptr);
        wait_for_the_end();
    }
    const int fd =
        register_pending(tmp)
            ? ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode)
            : kUntracked;
    const int saved = errno;
    if (fd == -1) unregister_pending(tmp);  // its slot free for the next output
    --g_creating;
    ::pthread_sigmask(SIG_SETMASK, &before, nullptr);
    errno = saved;
    return fd;
}

// Runs `step`, which works on temporary files; if a signal's handler removed them meanwhile
// the step may fail (the file to reopen or rename is gone): then the process is ending, and
// the error would only race the signal to the exit status.
template <typename Step>
void unless_signalled(Step&& step) {
    try {
        step();
    } catch (...) {
        if (g_signalled.load()) wait_for_the_end();
        throw;
    }
}

extern "C" void remove_pending_and_exit(int sig) {
    g_signalled = true;
    // The creating thread keeps this signal off; its section is one open() long.
    while (g_creating.load() > 0) {
    }
    unlink_pending();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

std::string temporary_name(const std::string& path) {
    static std::atomic<int> counter{0};
    const auto slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    return dir + "." + base + ".tmp." + std::to_string(::getpid()) + "." +
           std::to_string(counter++);
}

}  // namespace

void remove_pending_outputs() { unlink_pending(); }

void install_signal_cleanup() {
    std::signal(SIGINT, remove_pending_and_exit);
    std::signal(SIGTERM, remove_pending_and_exit);
    std::signal(SIGHUP, remove_pending_and_exit);
}

OutputSet::~OutputSet() {
    for (const auto& [tmp, final_path] : files_) {
        std::remove(tmp.c_str());
        unregister_pending(tmp);
    }
}

namespace {

namespace fs = std::filesystem;

// Set by add_output_options: one command per process, so a process-wide setting.
bool g_replace_read_only = false;

// Whether write_through may create `target`. A temporary file is created empty beforehand
// (create_pending), and is then only reopened: opened again by name with O_CREAT, it would be
// created anew if a signal's handler had just removed it.
enum class Creation { Allowed, Never };

// Opens `target` and runs the writer into it; errors name `path`, the file the user asked for.
void write_through(const std::string& target, const std::string& path,
                   const std::function<void(std::ostream&)>& writer, Creation creation) {
    // in|out is fopen's "r+": the file must exist, and is not truncated.
    std::ofstream out(target, creation == Creation::Never
                                  ? std::ios::binary | std::ios::in | std::ios::out
                                  : std::ios::binary | std::ios::trunc);
    if (!out) throw CliError(kExitOutput, path + ": cannot write (" + std::strerror(errno) + ")");
    try {
        writer(out);
    } catch (const Error& e) {
        throw CliError(kExitOutput, e.located(path));
    }
    out.flush();
    if (!out) throw CliError(kExitOutput, path + ": write failed (" + std::strerror(errno) + ")");
    out.close();
    if (out.fail())
        throw CliError(kExitOutput, path + ": write failed (" + std::strerror(errno) + ")");
}

// Flushes a finished file's data to the disk before it is renamed into place, so that a
// power cut never leaves an empty or partial file under the final name (the rename itself
// is atomic, but the data may still be in the page cache). `path` is the user's name.
void sync_file(const std::string& file, const std::string& path) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        throw CliError(kExitOutput,
                       path + ": cannot reopen the finished file (" + std::strerror(errno) + ")");
    const int rc = ::fsync(fd);
    const int saved = errno;
    ::close(fd);
    // EINVAL: the file system cannot sync (some special ones); nothing more can be done.
    if (rc != 0 && saved != EINVAL)
        throw CliError(kExitOutput,
                       path + ": cannot flush to the disk (" + std::strerror(saved) + ")");
}

std::string directory_of(const std::string& path) {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

// After the renames: the directory entry too, best effort (not every file system allows a
// directory to be opened and synced, and the data are already safe).
void sync_directory_of(const std::string& path) {
    const int fd = ::open(directory_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    (void)::fsync(fd);
    ::close(fd);
}

// The file a name finally designates: symbolic links at the last component followed (at
// most 40, as the kernel does), a relative target read from the link's directory. Renaming
// a temporary file over this name replaces the content the user meant, not the link.
std::string final_target(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return path;
    if (::stat(path.c_str(), &st) == 0) {
        // A device or a pipe is written in place under the name given (/dev/stdout is a link
        // to /proc/self/fd/1, whose "target" may be no path at all).
        if (!S_ISREG(st.st_mode)) return path;
        if (char* real = ::realpath(path.c_str(), nullptr)) {
            std::string out(real);
            std::free(real);
            return out;
        }
    }
    // A dangling link: the file it names is created.
    std::string p = path;
    for (int i = 0; i < 40; ++i) {
        struct stat st {};
        if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
        std::error_code ec;
        fs::path t = fs::read_symlink(p, ec);
        if (ec) return p;
        if (t.is_relative()) t = fs::path(p).parent_path() / t;
        p = t.string();
    }
    throw CliError(kExitOutput, path + ": too many levels of symbolic links");
}

// Inside an output directory another user may plant links (a shared cluster directory):
// the name and its directory must be what they look like, never a link.
void check_not_planted(const std::string& path) {
    struct stat st {};
    const std::string dir = directory_of(path);
    if (::lstat(dir.c_str(), &st) == 0 && S_ISLNK(st.st_mode))
        throw CliError(kExitOutput, path + ": its directory '" + dir +
                                        "' is a symbolic link; geotex does not write through "
                                        "links inside an output directory");
    if (::lstat(path.c_str(), &st) != 0) return;
    if (S_ISLNK(st.st_mode))
        throw CliError(kExitOutput, path +
                                        ": is a symbolic link; geotex does not write "
                                        "through links inside an output directory");
    if (!S_ISREG(st.st_mode))
        throw CliError(kExitOutput, path + ": is not a regular file; not replaced");
}

bool read_only(const std::string& path, const struct stat& st) {
    // No write bit at all counts even for root, whom access() always allows.
    return (st.st_mode & 0222) == 0 || ::access(path.c_str(), W_OK) != 0;
}

[[noreturn]] void refuse_read_only(const std::string& path) {
    throw CliError(kExitOutput, path +
                                    ": is read-only (no write permission); not replaced "
                                    "(--replace-read-only replaces it, keeping its permissions)");
}

}  // namespace

void add_output_options(CLI::App& sub) {
    sub.add_flag("--replace-read-only", g_replace_read_only,
                 "Replace an existing output file that has no write permission (it keeps its "
                 "permissions); without it such a file is refused before any work");
}

InputFiles::InputFiles(std::initializer_list<InputPath> inputs) {
    for (const InputPath& i : inputs) add(i);
}

void InputFiles::add(const InputPath& input) {
    struct stat st {};
    if (input.path.empty() || ::stat(input.path.c_str(), &st) != 0) return;
    files_.push_back(
        {{static_cast<unsigned long long>(st.st_dev), static_cast<unsigned long long>(st.st_ino)},
         input});
}

const InputPath* InputFiles::same_file_as(const std::string& path) const {
    struct stat st {};
    if (files_.empty() || ::stat(path.c_str(), &st) != 0) return nullptr;
    const std::pair<unsigned long long, unsigned long long> id{st.st_dev, st.st_ino};
    for (const auto& [file_id, input] : files_)
        if (file_id == id) return &input;
    return nullptr;
}

void check_output_paths(const std::vector<OutputPath>& outputs, const InputFiles& inputs) {
    std::vector<std::pair<std::filesystem::path, const OutputPath*>> files;
    for (const OutputPath& o : outputs) {
        if (o.path.empty()) {
            if (o.required) throw CliError(kExitUsage, o.option + ": empty file name");
            continue;
        }
        if (o.inside_output_dir) check_not_planted(o.path);
        const std::string target = final_target(o.path);
        struct stat st {};
        if (::stat(target.c_str(), &st) == 0) {
            if (S_ISDIR(st.st_mode)) throw CliError(kExitOutput, o.path + ": is a directory");
            if (!S_ISREG(st.st_mode)) continue;  // a device or a pipe, written in place
            if (const InputPath* in = inputs.same_file_as(target))
                throw CliError(kExitUsage, o.option + " '" + o.path +
                                               "' is the same file as the input " + in->what +
                                               " '" + in->path +
                                               "': an output never replaces an input");
            if (!g_replace_read_only && read_only(target, st)) refuse_read_only(o.path);
        }
        std::error_code ec;
        std::filesystem::path canonical = std::filesystem::absolute(target, ec);
        if (!ec) canonical = std::filesystem::weakly_canonical(canonical, ec);
        for (const auto& [other, first] : files)
            if (!ec && other == canonical)
                throw CliError(kExitUsage, first->option + " and " + o.option +
                                               " name the same file '" + o.path + "'");
        if (!ec) files.emplace_back(canonical, &o);
        // The temporary file is created next to the file finally written (a link's target).
        const std::string dir = directory_of(target);
        if (::stat(dir.c_str(), &st) != 0)
            throw CliError(kExitOutput, o.path + ": cannot write: directory '" + dir +
                                            "': " + std::strerror(errno));
        if (!S_ISDIR(st.st_mode))
            throw CliError(kExitOutput,
                           o.path + ": cannot write: '" + dir + "' is not a directory");
        // The temporary file is created next to the output, so the directory must be
        // writable even when the output already exists.
        if (::access(dir.c_str(), W_OK | X_OK) != 0)
            throw CliError(kExitOutput, o.path + ": cannot write in directory '" + dir + "' (" +
                                            std::strerror(errno) + ")");
    }
}

void OutputSet::add(const std::string& path, const std::function<void(std::ostream&)>& writer) {
    const bool refuse_links = links_ == OutputLinks::Refuse;
    if (refuse_links) check_not_planted(path);
    const std::string target = refuse_links ? path : final_target(path);
    // An existing path that is not a regular file (/dev/null, a pipe, a device) is written
    // in place: renaming a temporary file over it would replace the device itself.
    struct stat st {};
    const bool exists = ::stat(target.c_str(), &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) {
        if (S_ISDIR(st.st_mode)) throw CliError(kExitOutput, path + ": is a directory");
        write_through(target, path, writer, Creation::Allowed);
        return;
    }
    if (exists && !g_replace_read_only && read_only(target, st)) refuse_read_only(path);
    const std::string tmp = temporary_name(target);
    files_.emplace_back(tmp, target);
    unless_signalled([&] {
        // Created here, exclusively and not through a link: a replaced file's content is never
        // readable by more users than the file it replaces (0600 until its mode is copied).
        const int fd = create_pending(tmp, exists ? 0600 : 0666);
        if (fd == kUntracked)
            throw CliError(kExitOutput,
                           path + ": cannot write: " + std::to_string(kMaxPending) +
                               " output files are being written already, the most that an "
                               "interrupted run removes, or the temporary file's name is too long");
        if (fd < 0)
            throw CliError(kExitOutput, path + ": cannot create a temporary file in '" +
                                            directory_of(target) + "' (" + std::strerror(errno) +
                                            ")");
        ::close(fd);
        write_through(tmp, path, writer, Creation::Never);
        if (exists) {
            // The owner can be kept only by root (and the group by a member of it): best
            // effort; otherwise the file becomes the user's, as with any editor's save. Before
            // chmod, since chown clears set-id bits.
            if (st.st_uid != ::geteuid() || st.st_gid != ::getegid()) {
                const int kept = ::chown(tmp.c_str(), st.st_uid, st.st_gid);
                (void)kept;
            }
            if (::chmod(tmp.c_str(), st.st_mode & 07777) != 0)
                throw CliError(kExitOutput, path + ": cannot keep its permissions (" +
                                                std::strerror(errno) + ")");
        }
        sync_file(tmp, path);
    });
}

void OutputSet::commit() {
    for (const auto& [tmp, final_path] : files_) {
        unless_signalled([&, &tmp = tmp, &final_path = final_path] {
            if (std::rename(tmp.c_str(), final_path.c_str()) != 0)
                throw CliError(kExitOutput, final_path +
                                                ": cannot rename the finished file into place (" +
                                                std::strerror(errno) + ")");
        });
        unregister_pending(tmp);
    }
    std::vector<std::string> dirs;  // each directory once
    for (const auto& file : files_) {
        const std::string dir = directory_of(file.second);
        if (std::find(dirs.begin(), dirs.end(), dir) == dirs.end()) {
            dirs.push_back(dir);
            sync_directory_of(file.second);
        }
    }
    files_.clear();
}

std::string time_left(double seconds, long long done, long long total) {
    if (done <= 0 || total <= 0) return {};
    const double left =
        seconds * static_cast<double>(std::max(0LL, total - done)) / static_cast<double>(done);
    char text[32];
    if (left < 90)
        std::snprintf(text, sizeof text, "%.0f s", std::max(1.0, left));
    else if (left < 5400)
        std::snprintf(text, sizeof text, "%.0f min", left / 60);
    else
        std::snprintf(text, sizeof text, "%.1f h", left / 3600);
    return text;
}

Progress::Progress(bool quiet) : quiet_(quiet), tty_(::isatty(STDERR_FILENO) != 0) {
    begin_work_lines();
}

void Progress::begin_work_lines() {
    if (quiet_ || !tty_ || work_) return;
    // Called from a worker thread of the loop; the stage it reads was set before the loop
    // began, on this thread.
    work_ = std::make_unique<WorkProgressScope>([this](const WorkProgress& w) {
        if (w.done <= 0 || w.total <= 0) return;
        std::fprintf(
            stderr, "geotex: %-28s %3d%%, about %s left\033[K\r", current_.c_str(),
            static_cast<int>(100.0 * static_cast<double>(w.done) / static_cast<double>(w.total)),
            time_left(w.seconds, w.done, w.total).c_str());
    });
}

Progress::~Progress() = default;

void Progress::end_work_lines() { work_.reset(); }

void Progress::operator()(const StageEvent& e) {
    if (e.seconds < 0) {
        current_ = e.stage;
        if (!quiet_ && tty_) std::fprintf(stderr, "geotex: %-28s ...\033[K\r", e.stage.c_str());
        return;
    }
    stages_.emplace_back(e.stage, e.seconds);
    // On a terminal the line may hold a longer work line of the stage: cleared to its end.
    if (!quiet_)
        std::fprintf(stderr, "geotex: %-28s %8.3f s%s\n", e.stage.c_str(), e.seconds,
                     tty_ ? "\033[K" : "");
}

void Progress::note(const std::string& line) const {
    if (!quiet_) std::fprintf(stderr, "geotex: %s\n", line.c_str());
}

void warn(const std::string& message) {
    std::fprintf(stderr, "geotex: warning: %s\n", message.c_str());
}

}  // namespace geotex::cli
