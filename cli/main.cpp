// geotex: salient geometric details ("3D texels") of triangle meshes, their geometric
// textures, and (later stages) their semantic annotation as linked data.

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <new>
#include <stdexcept>
#include <system_error>

#include "cli/commands.hpp"
#include "cli/mesh_input.hpp"
#include "cli/output.hpp"
#include "common/detail/text.hpp"
#include "common/errors.hpp"

namespace geotex::cli {

using detail::message_text;

void add_common_options(CLI::App& sub, CommonOptions& common) {
    sub.add_flag("-q,--quiet", common.quiet,
                 "No progress messages on stderr (errors and warnings still show)");
    sub.add_option("-j,--threads", common.threads,
                   "Worker threads (default: all cores; 1: no thread is started); results do not "
                   "depend on it")
        ->check(CLI::Range(1, 1024))
        ->default_str("all");  // the member's 0 means "all cores", which is no valid value
}

void refuse_non_finite_numbers(CLI::App& app) {
    // CLI11 converts "nan", "inf" and "1e999" into doubles without complaint, and its Range
    // check lets NaN through (every comparison with NaN is false): one validator, attached
    // here to every floating option of every subcommand, refuses them at parse time. CLI11
    // names an option's type FLOAT when it converts to a floating type, so an option added
    // later gets the check without anyone remembering it.
    const CLI::Validator finite(
        [](std::string& text) {
            double value = 0;
            if (!CLI::detail::lexical_cast(text, value)) return std::string();  // CLI11 reports it
            if (std::isfinite(value)) return std::string();
            return "not a finite number: '" + text + "'";
        },
        "");
    // transform(), unlike check(), puts the validator first, before any Range check, so every
    // such value gets the same message.
    for (CLI::Option* option : app.get_options())
        if (option->get_type_name().rfind("FLOAT", 0) == 0) option->transform(finite);
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        refuse_non_finite_numbers(*sub);
}

std::unique_ptr<tbb::global_control> limit_threads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 static_cast<std::size_t>(threads));
}

namespace {

// What an exception says when the machine ran out (memory, address space, threads), or
// nullptr for any other exception. It also runs in the terminate handler: it allocates
// nothing itself (the rethrow is served by the runtime's emergency pool when memory is out).
const char* exhaustion(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const std::bad_alloc&) {
        return "out of memory";
    } catch (const std::system_error& e) {
        // std::thread's constructor: EAGAIN when no thread (its stack) can be created.
        if (e.code() == std::errc::resource_unavailable_try_again ||
            e.code() == std::errc::not_enough_memory)
            return "out of memory (no thread can be started)";
    } catch (const std::runtime_error& e) {
        // TBB's words when it cannot start a worker (oneTBB src/tbb/rml_thread_monitor.h).
        if (std::strncmp(e.what(), "pthread_create has failed", 25) == 0)
            return "out of memory (no thread can be started)";
    } catch (...) {
    }
    return nullptr;
}

// The one line of an error that names no file itself: the input being worked on comes first.
void print_located(const char* what) {
    const char* input = current_input();
    try {
        if (*input != '\0') {
            std::fprintf(stderr, "geotex: error: %s: %s\n", message_text(input).c_str(), what);
            return;
        }
    } catch (...) {  // no memory left even for the escaped name
    }
    std::fprintf(stderr, "geotex: error: %s\n", what);
}

// An exception thrown where it cannot be caught (TBB starting a worker from inside a
// noexcept function when pthread_create fails) ends in std::terminate: report it on one
// line with the processing exit code instead of an abort (SIGABRT, exit 134).
[[noreturn]] void on_terminate() {
    const std::exception_ptr error = std::current_exception();
    const char* what = error ? exhaustion(error) : nullptr;
    print_located(what != nullptr ? what
                                  : "internal error: the process was ended (std::terminate)");
    std::fflush(stderr);
    remove_pending_outputs();  // _Exit runs no destructor: no partial output is left
    std::_Exit(kExitProcessing);
}

}  // namespace

int run_command(const Runner& run) {
    try {
        return run();
    } catch (const CliError& e) {
        std::fprintf(stderr, "geotex: error: %s\n", message_text(e.what()).c_str());
        return e.code();
    } catch (const geotex::Error& e) {
        std::fprintf(stderr, "geotex: error: %s\n", message_text(e.located()).c_str());
        return kExitProcessing;
    } catch (const std::exception& e) {
        if (const char* what = exhaustion(std::current_exception())) {
            print_located(what);
        } else {
            std::fprintf(stderr, "geotex: error: internal error: %s\n",
                         message_text(e.what()).c_str());
        }
        return kExitProcessing;
    }
}

}  // namespace geotex::cli

int main(int argc, char** argv) {
    using namespace geotex::cli;
    std::set_terminate(on_terminate);
    CLI::App app{
        "geotex finds the salient geometric details (3D texels) of a triangle mesh at a scale you\n"
        "choose and groups them into geometric textures (Othmani, Torkhani & Favreau 2019).\n"};
    app.name("geotex");
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("geotex ") + GEOTEX_VERSION);
    app.footer(
        "Run 'geotex <command> --help' for the options of a command.\n"
        "Exit codes: 0 ok, 1 usage, 2 bad input, 3 processing failed (out of memory too), 4 cannot "
        "write\n"
        "output, 5 (dict fit) written but some marks not reproduced.");

    std::map<CLI::App*, Runner> runners;
    CLI::App* synth = app.add_subcommand(
        "synth", "Generate the paper's synthetic benchmark sphere and its ground truth");
    runners[synth] = add_synth(*synth);
    CLI::App* segment = app.add_subcommand(
        "segment", "Find texels and textures of a mesh; write a coloured segmentation PLY");
    runners[segment] = add_segment(*segment);
    CLI::App* annotate = app.add_subcommand(
        "annotate", "The whole pipeline: textures named with dictionary concepts, written as RDF");
    runners[annotate] = add_annotate(*annotate);
    CLI::App* batch = app.add_subcommand(
        "batch",
        "Annotate a whole collection (directory or CSV manifest), resumable and shardable");
    runners[batch] = add_batch(*batch);
    CLI::App* dict = app.add_subcommand(
        "dict", "Check a YAML interval dictionary, or publish it as a SKOS concept scheme");
    runners[dict] = add_dict(*dict);
    CLI::App* query = app.add_subcommand(
        "query", "Run a SPARQL query over geotex RDF output (embedded, no server)");
    runners[query] = add_query(*query);
    CLI::App* publish = app.add_subcommand(
        "publish",
        "Send the objects of a batch output directory to a triple store, or write N-Quads");
    runners[publish] = add_publish(*publish);
    CLI::App* scales = app.add_subcommand(
        "scales", "Segment a mesh over a series of scales and recommend the stable ones");
    runners[scales] = add_scales(*scales);
    CLI::App* evaluate = app.add_subcommand(
        "evaluate", "Score a segmentation against a ground truth (Hausdorff distance, matching)");
    runners[evaluate] = add_evaluate(*evaluate);
    CLI::App* render = app.add_subcommand(
        "render", "Draw a mesh or a segmentation to a PNG picture (no viewer needed)");
    runners[render] = add_render(*render);
    CLI::App* view = app.add_subcommand(
        "view", "Serve the curator's workbench in the browser: objects, words, dictionary edits");
    runners[view] = add_view(*view);
    refuse_non_finite_numbers(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "geotex: error: %s (see 'geotex --help')\n",
                     message_text(e.what()).c_str());
        return kExitUsage;
    }
    install_signal_cleanup();
    for (auto& [sub, run] : runners)
        if (sub->parsed()) return run_command(run);
    return kExitUsage;
}
