#pragma once
// Command-line plumbing: errors with exit codes, all-or-nothing output files, progress.

#include <array>
#include <chrono>
#include <functional>
#include <initializer_list>
#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "common/errors.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/work_progress.hpp"

namespace CLI {
class App;
}

namespace geotex::cli {

/// Exit codes (STYLE.md): usage, input, processing, output.
enum ExitCode { kExitUsage = 1, kExitInput = 2, kExitProcessing = 3, kExitOutput = 4 };

/// An error already formatted for the user ("<file>: <what>"), with its exit code.
class CliError : public std::runtime_error {
  public:
    CliError(int code, const std::string& message) : std::runtime_error(message), code_(code) {}
    int code() const { return code_; }

  private:
    int code_;
};

/// Runs fn; a geotex::Error thrown inside becomes a CliError with `code`, located in
/// `file` when the error does not name its own file.
template <class Fn>
auto in_phase(int code, const std::string& file, Fn&& fn) -> decltype(fn());

/// Runs fn, which writes scratch files: their failure (a full disk) is an IoError naming the
/// directory, and becomes a CliError with kExitOutput, the output directory's, not the input's.
template <class Fn>
auto on_scratch(Fn&& fn) -> decltype(fn());

/// An output file named on the command line, for check_output_paths.
struct OutputPath {
    std::string option;     ///< e.g. "--json", for messages
    std::string path;       ///< empty: the output was not asked for
    bool required = false;  ///< an empty path is then an error
    /// A file geotex creates inside an output directory (OUTDIR/summary.csv, ...): a
    /// symbolic link or a non-regular file there is refused, never written through.
    bool inside_output_dir = false;
};

/// An input file of the command (mesh, dictionary, manifest, ...), for check_output_paths.
struct InputPath {
    std::string what;  ///< e.g. "MESH", "--dictionary", for messages
    std::string path;  ///< empty: none
};

/// The identities (device, inode, after following symbolic links) of the existing input
/// files of a command, built once, so that outputs can be checked against many inputs.
class InputFiles {
  public:
    InputFiles() = default;
    InputFiles(std::initializer_list<InputPath> inputs);
    void add(const InputPath& input);
    /// The input that is the same file as `path` (which must exist), or nullptr.
    const InputPath* same_file_as(const std::string& path) const;

  private:
    std::vector<std::pair<std::pair<unsigned long long, unsigned long long>, InputPath>> files_;
};

/// Checks, before any work, what would make writing fail at the end of a long run or lose
/// data: an empty name, two options naming the same file, an output that is one of the
/// command's input files (same device and inode, links followed), a directory as output, a
/// directory that does not exist or cannot be written, an existing read-only file (unless
/// --replace-read-only), and inside an output directory a symbolic link or a non-regular
/// file. Throws CliError: kExitUsage for a name (including an output naming an input),
/// kExitOutput (the code the write would fail with) for the file system.
void check_output_paths(const std::vector<OutputPath>& outputs, const InputFiles& inputs = {});

/// How an OutputSet treats a symbolic link at an output's name.
enum class OutputLinks {
    Follow,  ///< write the link's target (the link stays a link): a name the user gave
    Refuse,  ///< refuse a link (and a non-regular file) at the name or as its directory: a
             ///< file geotex creates inside an output directory, where a link may be planted
};

/// Adds --replace-read-only to a subcommand that writes files; it acts on every OutputSet.
void add_output_options(CLI::App& sub);

/// Output files written all or nothing: each is written to a temporary name in the target
/// directory; commit() renames them all into place. Files not committed (an error, an
/// interrupt) are removed, so a failed run never leaves a partial or stale-looking output.
/// A replaced file keeps its permissions (and, where allowed, its owner); a symbolic link
/// is written through (its target replaced, the link kept) unless OutputLinks::Refuse; an
/// existing device or pipe (/dev/stdout, a FIFO) is written in place, never replaced.
class OutputSet {
  public:
    explicit OutputSet(OutputLinks links = OutputLinks::Follow) : links_(links) {}
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;
    ~OutputSet();

    /// Writes `path` (to a temporary file for now) with `writer`. Throws CliError
    /// (kExitOutput) when the file cannot be written or is refused.
    void add(const std::string& path, const std::function<void(std::ostream&)>& writer);

    /// Renames every temporary file into place.
    void commit();

  private:
    OutputLinks links_;
    std::vector<std::pair<std::string, std::string>> files_;  // (temporary, final)
};

/// Prints stage progress on stderr unless quiet: a line per finished stage with its time. On
/// a terminal, a long stage (a loop of a second or more: reading a large text mesh, the disc
/// means, the depth map of a large scan) also shows how far it is and about how long is
/// left, on the line of the stage, rewritten in place (work_progress.hpp).
class Progress {
  public:
    explicit Progress(bool quiet);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    void operator()(const StageEvent& event);
    /// A free-form progress line.
    void note(const std::string& line) const;
    /// Time of each finished stage, in order.
    const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }
    /// No lines of how far a loop is until begin_work_lines(): for work that runs several
    /// loops at once (the scale series), whose lines would mix.
    void end_work_lines();
    void begin_work_lines();

  private:
    bool quiet_;
    bool tty_;
    std::string current_;  // the stage running, for its work lines
    std::vector<std::pair<std::string, double>> stages_;
    std::unique_ptr<WorkProgressScope> work_;
};

/// How a progress line says the time left of a loop that has done `done` of `total` units in
/// `seconds`, at the pace so far: "12 s", "4 min", "1.5 h"; empty before the first unit.
std::string time_left(double seconds, long long done, long long total);

/// Prints a warning line on stderr ("geotex: warning: ...").
void warn(const std::string& message);

/// Times a block of CLI work as a stage; a stage that throws is not reported.
template <class Fn>
auto timed_stage(Progress& progress, const std::string& stage, Fn&& fn) -> decltype(fn()) {
    progress({stage, -1.0});
    const auto start = std::chrono::steady_clock::now();
    auto seconds = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    if constexpr (std::is_void_v<decltype(fn())>) {
        fn();
        progress({stage, seconds()});
    } else {
        auto result = fn();
        progress({stage, seconds()});
        return result;
    }
}

/// Installs SIGINT/SIGTERM handlers that remove pending temporary outputs before exiting.
void install_signal_cleanup();

/// Removes the temporary files of every output not yet committed, for an end that skips the
/// destructors (the terminate handler's std::_Exit). Only unlink(2): safe where no allocation is.
void remove_pending_outputs();

template <class Fn>
auto in_phase(int code, const std::string& file, Fn&& fn) -> decltype(fn()) {
    try {
        return fn();
    } catch (const Error& e) {
        throw CliError(code, e.located(file));
    }
}

template <class Fn>
auto on_scratch(Fn&& fn) -> decltype(fn()) {
    try {
        return fn();
    } catch (const IoError& e) {
        throw CliError(kExitOutput, e.located());
    }
}

}  // namespace geotex::cli
