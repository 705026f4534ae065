#pragma once
// Subcommands of the geotex command. Each add_* registers its options on `app` and returns
// the function that runs it after parsing (returning the exit code).

#include <tbb/global_control.h>

#include <functional>
#include <memory>

// CLI11 declared only: it is header-only, and every source that includes it pays seconds of
// compile time (15 s under the sanitizers) even when it uses none of it; the sources that
// register options include <CLI/CLI.hpp> themselves.
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace geotex::cli {

/// Options every subcommand has.
struct CommonOptions {
    bool quiet = false;  ///< no progress on stderr
    int threads = 0;     ///< 0: all cores
};

/// Adds --quiet and --threads to a subcommand.
void add_common_options(CLI::App& sub, CommonOptions& common);

/// Attaches to every option of `app` and its subcommands whose type is FLOAT (what CLI11
/// names a floating option) a check that refuses NaN and infinities ("nan", "-inf", "1e999")
/// as a usage error naming the option. Run once, after every subcommand has its options.
void refuse_non_finite_numbers(CLI::App& app);

/// Limits the worker threads for the lifetime of the returned object (0: no limit).
std::unique_ptr<tbb::global_control> limit_threads(int threads);

using Runner = std::function<int()>;

/// Runs a subcommand and returns its exit code; an exception it throws becomes the one line
/// "geotex: error: ..." on stderr and the exit code of its kind (CliError's own, 3 for a
/// geotex::Error, for running out of memory or threads and for anything unexpected).
int run_command(const Runner& run);

Runner add_synth(CLI::App& app);
Runner add_segment(CLI::App& app);
Runner add_evaluate(CLI::App& app);
Runner add_scales(CLI::App& app);
Runner add_render(CLI::App& app);
Runner add_annotate(CLI::App& app);
Runner add_batch(CLI::App& app);
Runner add_dict(CLI::App& app);
Runner add_query(CLI::App& app);
Runner add_publish(CLI::App& app);
Runner add_view(CLI::App& app);

}  // namespace geotex::cli
