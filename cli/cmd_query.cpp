// geotex query: SPARQL over geotex output, embedded (Rasqal over an indexed store).

#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/dictionary_input.hpp"
#include "cli/output.hpp"
#include "ontology/sparql.hpp"

namespace geotex::cli {

namespace {

struct QueryOptions {
    CommonOptions common;
    std::string query;
    std::vector<std::string> data;
    std::string format = "table";
};

int run_query(const QueryOptions& o) {
    static const std::map<std::string, ResultFormat> formats = {
        {"table", ResultFormat::Table}, {"csv", ResultFormat::Csv}, {"json", ResultFormat::Json}};
    auto threads = limit_threads(o.common.threads);
    const std::string text = read_text_file(o.query);
    const QueryResult result = in_phase(kExitInput, o.query, [&] { return run_sparql(text, o.data); });
    write_query_result(std::cout, result, formats.at(o.format));
    std::cout.flush();
    return 0;
}

}  // namespace

Runner add_query(CLI::App& sub) {
    auto o = std::make_shared<QueryOptions>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "Run a SPARQL SELECT or ASK query over one or more RDF files (Turtle, N-Triples, N-Quads, RDF/XML)\n"
        "written by geotex, without a server (Rasqal over an indexed store; the files are read on --threads\n"
        "cores). ontology/queries/ holds documented queries. Property paths p/q, ^p, p|q and !p are rewritten\n"
        "into triple patterns; p*, p+, p?, FILTER [NOT] EXISTS and MINUS are not supported\n"
        "(ontology/queries/README.md).");
    sub.add_option("query", o->query, "SPARQL query file (.rq)")->required();
    sub.add_option("data", o->data, "RDF files to query (their union)")->required();
    sub.add_option("--format", o->format, "table, csv or SPARQL 1.1 results json")->check(CLI::IsMember({"table", "csv", "json"}));
    add_common_options(sub, o->common);
    return [o] { return run_query(*o); };
}

}  // namespace geotex::cli
