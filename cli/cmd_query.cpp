// geotex query: SPARQL over geotex output, embedded (Rasqal over an indexed store).

#include <sys/time.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/dictionary_input.hpp"
#include "cli/output.hpp"
#include "common/detail/text.hpp"
#include "ontology/sparql.hpp"

namespace geotex::cli {

namespace {

struct QueryOptions {
    CommonOptions common;
    std::string query;
    std::vector<std::string> data;
    std::string format = "table";
    double timeout = 300;  // seconds, 0: none
};

/// Seconds that the engine is given, past --timeout, to stop by itself before the watchdog
/// ends the process.
constexpr double kWatchdogGrace = 5;

/// The line the watchdog prints, prepared before it is armed: a signal handler may not
/// allocate.
std::string g_watchdog_line;

extern "C" void on_watchdog_alarm(int) {
    [[maybe_unused]] const ssize_t written =
        ::write(STDERR_FILENO, g_watchdog_line.data(), g_watchdog_line.size());
    std::_Exit(kExitProcessing);
}

/// Ends the process with the timeout's error when the query has not finished `seconds` from
/// now. run_sparql stops at its deadline wherever Rasqal asks geotex's store for triples or
/// hands out a row; a loop inside Rasqal that does neither (a cross product of VALUES blocks,
/// say) would not stop, and Rasqal cannot be cancelled. Nothing has been written to stdout
/// while the watchdog runs, so ending the process loses no output. A POSIX interval timer
/// (SIGALRM) rather than a thread: geotex -j1 starts no thread, and nothing can fail to start.
class Watchdog {
  public:
    Watchdog(double seconds, const std::string& message) {
        if (seconds <= 0) return;
        g_watchdog_line = "geotex: error: " + detail::message_text(message) + "\n";
        std::signal(SIGALRM, on_watchdog_alarm);
        const double capped = std::min(seconds, 1e9);  // about 31 years; setitimer's range
        itimerval timer{};
        timer.it_value.tv_sec = static_cast<time_t>(capped);
        timer.it_value.tv_usec = static_cast<suseconds_t>((capped - std::floor(capped)) * 1e6);
        if (timer.it_value.tv_sec == 0 && timer.it_value.tv_usec == 0) timer.it_value.tv_usec = 1;
        armed_ = ::setitimer(ITIMER_REAL, &timer, nullptr) == 0;
    }
    ~Watchdog() { stop(); }
    Watchdog(const Watchdog&) = delete;
    Watchdog& operator=(const Watchdog&) = delete;

    void stop() {
        if (!armed_) return;
        itimerval off{};
        ::setitimer(ITIMER_REAL, &off, nullptr);
        armed_ = false;
    }

  private:
    bool armed_ = false;
};

int run_query(const QueryOptions& o) {
    static const std::map<std::string, ResultFormat> formats = {
        {"table", ResultFormat::Table}, {"csv", ResultFormat::Csv}, {"json", ResultFormat::Json}};
    if (!(o.timeout >= 0) || !std::isfinite(o.timeout))
        throw CliError(kExitUsage, "--timeout must be a number of seconds >= 0 (0: none)");
    auto threads = limit_threads(o.common.threads);
    const std::string text = read_text_file(o.query);
    QueryParams params;
    params.timeout = o.timeout;
    char limit[32];
    std::snprintf(limit, sizeof limit, "%g", o.timeout);
    const std::string timeout_message = o.query + ": the query ran out of time: the --timeout of " +
                                        limit +
                                        " s passed before it finished; no result is written";
    Watchdog watchdog(o.timeout > 0 ? o.timeout + kWatchdogGrace : 0, timeout_message);
    const QueryResult result = in_phase(kExitInput, o.query, [&] {
        try {
            return run_sparql(text, o.data, params);
        } catch (const QueryTimeout&) {
            throw CliError(kExitProcessing, timeout_message);
        }
    });
    watchdog.stop();
    write_query_result(std::cout, result, formats.at(o.format));
    std::cout.flush();
    return 0;
}

}  // namespace

Runner add_query(CLI::App& sub) {
    auto o = std::make_shared<QueryOptions>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "Run a SPARQL SELECT or ASK query over one or more RDF files (Turtle, N-Triples, N-Quads, "
        "RDF/XML)\n"
        "written by geotex, without a server (Rasqal over an indexed store; the files are read on "
        "--threads\n"
        "cores). ontology/queries/ holds documented queries. Property paths p/q, ^p, p|q and !p "
        "are rewritten\n"
        "into triple patterns; p*, p+, p?, FILTER [NOT] EXISTS and MINUS are not supported\n"
        "(ontology/queries/README.md). The query reads the data files and nothing else: FROM, "
        "SERVICE,\n"
        "LOAD and updates are refused. A UTF-8 byte order mark at the start of the query file is "
        "skipped.\n"
        "In the table and CSV, a U+0000 character of a value is written as the six characters "
        "\\u0000\n"
        "(JSON escapes it as \\u0000 too).");
    sub.add_option("query", o->query, "SPARQL query file (.rq)")->required();
    sub.add_option("data", o->data, "RDF files to query (their union)")->required();
    sub.add_option("--format", o->format, "table, csv or SPARQL 1.1 results json")
        ->check(CLI::IsMember({"table", "csv", "json"}));
    sub.add_option(
           "--timeout", o->timeout,
           "Seconds allowed for reading the data and running the query (0: no limit); when they\n"
           "run out, the query stops with an error (exit 3) and writes no result")
        ->type_name("SECONDS");
    add_common_options(sub, o->common);
    return [o] { return run_query(*o); };
}

}  // namespace geotex::cli
