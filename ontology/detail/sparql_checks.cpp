#include "ontology/detail/sparql_checks.hpp"

#include <vector>

#include "common/errors.hpp"
#include "ontology/detail/sparql_tokens.hpp"

namespace geotex::detail {

void refuse_service(const std::string& query) {
    for (const SparqlToken& t : tokenize_sparql(query))
        if (is_keyword(query, t, "SERVICE"))
            throw InvalidInput(
                "SERVICE is refused: geotex query reads only the data files it is given, "
                "never a URI (query the other endpoint apart and give its results as a file)",
                "", t.line, t.column);
}

void refuse_updates(const std::string& query) {
    // No keyword of SPARQL 1.1 Update is a word of the query language, so any of them, outside
    // strings, IRIs and comments, makes the text an update. Refused here rather than left to
    // Rasqal's parser, which refuses them too but leaks what it had built.
    static const char* const kUpdateWords[] = {"LOAD", "CLEAR", "DROP",   "CREATE", "ADD",
                                               "MOVE", "COPY",  "INSERT", "DELETE", "WITH"};
    for (const SparqlToken& t : tokenize_sparql(query))
        for (const char* word : kUpdateWords)
            if (is_keyword(query, t, word))
                throw InvalidInput(std::string(word) +
                                       " is refused: geotex query runs queries (SELECT, ASK), "
                                       "never a SPARQL Update; it changes no data",
                                   "", t.line, t.column);
}

bool has_service(rasqal_graph_pattern* gp) {
    if (!gp) return false;
    if (rasqal_graph_pattern_get_operator(gp) == RASQAL_GRAPH_PATTERN_OPERATOR_SERVICE) return true;
    for (int i = 0;; ++i) {
        rasqal_graph_pattern* sub = rasqal_graph_pattern_get_sub_graph_pattern(gp, i);
        if (!sub) return false;
        if (has_service(sub)) return true;
    }
}

void check_values_form(const std::string& query) {
    const std::vector<SparqlToken> tokens = tokenize_sparql(query);
    for (std::size_t k = 0; k + 1 < tokens.size(); ++k)
        if (is_keyword(query, tokens[k], "VALUES") &&
            tokens[k + 1].kind == SparqlToken::Kind::Variable)
            throw InvalidInput(
                "Rasqal 0.9.33 returns wrong rows for (or crashes on) the one-variable form "
                "`VALUES ?x { ... }`: write it `VALUES (?x) { (...) (...) }`",
                "", tokens[k].line, tokens[k].column);
}

bool mentions_minus(const std::string& query) {
    for (const SparqlToken& t : tokenize_sparql(query))
        if (is_keyword(query, t, "MINUS")) return true;
    return false;
}

}  // namespace geotex::detail
