// libFuzzer target: the text of a SPARQL query, as `geotex query` takes it. The input is the
// query; it runs on a small graph built in memory (IRIs, a blank node, plain, language-tagged
// and typed literals, one holding U+0000) with a time limit of 2 s, through everything that
// run_sparql does: the checks that refuse a query (SERVICE, FROM, the one-variable VALUES),
// the rewriting of property paths and aggregates, the join order, Rasqal's parse and run, the
// solution modifiers, and the three result writers.
//
// Answers: geotex::Error (a ParseError from Rasqal, an InvalidInput refusal, a QueryTimeout).
// Invariants: a query holding the keyword SERVICE never runs; every row has one cell and one
// term per variable; the JSON results parse back with the same number of rows; the table ends
// with its row count.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "ontology/detail/sparql_run.hpp"
#include "ontology/detail/sparql_tokens.hpp"
#include "ontology/detail/triple_store.hpp"
#include "ontology/sparql.hpp"

namespace {

using namespace geotex;

std::string current_query;

void require(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_sparql: invariant broken: %s\n---- query:\n%s\n----\n", what,
                 current_query.c_str());
    std::abort();
}

/// The graph: ex:a ex:p ex:b (and a few more), as geotex's loader would have stored it.
void load_graph(detail::TripleStore& store, const detail::Deadline&) {
    const std::string ex = "http://ex.org/";
    const std::string xsd = "http://www.w3.org/2001/XMLSchema#";
    auto iri = [&](const std::string& local) {
        std::string key;
        detail::append_iri_key(key, ex + local);
        return store.intern(key);
    };
    auto literal = [&](const std::string& lexical, const std::string& language,
                       const std::string& datatype) {
        std::string key;
        detail::append_literal_key(key, lexical, language, datatype);
        return store.intern(key);
    };
    std::string blank_key;
    detail::append_blank_key(blank_key, "f0b0");
    const auto a = iri("a"), b = iri("b"), c = iri("c"), p = iri("p"), q = iri("q"), r = iri("r");
    const auto blank = store.intern(blank_key);
    std::string type_key;
    detail::append_iri_key(type_key, "http://www.w3.org/1999/02/22-rdf-syntax-ns#type");
    const auto type = store.intern(type_key);
    store.add(a, p, b);
    store.add(b, p, c);
    store.add(c, p, c);
    store.add(blank, p, a);
    store.add(a, type, iri("T"));
    store.add(a, q, literal("label", "en", ""));
    store.add(a, q, literal("étiquette", "fr", ""));
    store.add(b, q, literal(std::string("nul\0inside", 10), "", ""));
    store.add(a, r, literal("12", "", xsd + "integer"));
    store.add(b, r, literal("1.5E0", "", xsd + "double"));
    store.add(c, r, literal("true", "", xsd + "boolean"));
    store.finish();
}

bool has_service_keyword(const std::string& query) {
    for (const detail::SparqlToken& t : detail::tokenize_sparql(query))
        if (detail::is_keyword(query, t, "SERVICE")) return true;
    return false;
}

}  // namespace

// Rasqal 0.9.33's SPARQL parser leaks parts of the query on some syntax errors (a sequence, a
// variable, an expression: inside sparql_parser_parse, which no code of geotex calls but
// through rasqal_query_prepare). Those leaks are suppressed by the frame of the parser, which
// needs the full stack of each allocation (librasqal has no frame pointers); a query that
// geotex fails to free is rooted in rasqal_new_query and is still reported.
extern "C" const char* __lsan_default_suppressions() { return "leak:sparql_parser_parse\n"; }
extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    current_query.assign(reinterpret_cast<const char*>(data), size);
    QueryParams params;
    params.timeout = 2;
    QueryResult result;
    try {
        result = detail::run_sparql_with(current_query, load_graph, params);
    } catch (const Error&) {
        return 0;
    }
    // run_sparql skips a byte order mark; the tokenizer sees the rest.
    const std::string body =
        current_query.compare(0, 3, "\xEF\xBB\xBF") == 0 ? current_query.substr(3) : current_query;
    require(!has_service_keyword(body), "a query with SERVICE ran");
    require(result.rows.size() == result.terms.size(), "as many term rows as rows");
    for (std::size_t i = 0; i < result.rows.size(); ++i) {
        require(result.rows[i].size() == result.variables.size(), "one cell per variable");
        require(result.terms[i].size() == result.variables.size(), "one term per variable");
    }
    std::ostringstream json, table, csv;
    write_query_result(json, result, ResultFormat::Json);
    write_query_result(table, result, ResultFormat::Table);
    write_query_result(csv, result, ResultFormat::Csv);
    const auto doc = nlohmann::json::parse(json.str(), nullptr, false);
    require(!doc.is_discarded(), "the JSON results parse");
    if (result.is_boolean) {
        require(doc.contains("boolean"), "an ASK answer in JSON");
    } else {
        require(doc["results"]["bindings"].size() == result.rows.size(), "JSON rows");
        const std::string t = table.str();
        const std::string count = "(" + std::to_string(result.rows.size()) +
                                  (result.rows.size() == 1 ? " row)\n" : " rows)\n");
        require(t.size() >= count.size() &&
                    t.compare(t.size() - count.size(), count.size(), count) == 0,
                "the table ends with its row count");
    }
    return 0;
}
