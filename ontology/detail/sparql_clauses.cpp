#include "ontology/detail/sparql_clauses.hpp"

#include <algorithm>
#include <string_view>
#include <vector>

#include "ontology/detail/sparql_tokens.hpp"

namespace geotex::detail {

using Kind = SparqlToken::Kind;

std::string remove_order_by(const std::string& query) {
    const std::vector<SparqlToken> tokens = tokenize_sparql(query);
    auto is_word = [&](std::size_t k, std::string_view w) {
        return k < tokens.size() && is_keyword(query, tokens[k], w);
    };
    auto opens = [&](std::size_t k) {
        return is_punct(query, tokens[k], "{") || is_punct(query, tokens[k], "(");
    };
    auto closes = [&](std::size_t k) {
        return is_punct(query, tokens[k], "}") || is_punct(query, tokens[k], ")");
    };
    int depth = 0;
    for (std::size_t k = 0; k < tokens.size(); ++k) {
        if (opens(k)) ++depth;
        if (closes(k)) --depth;
        if (depth != 0 || !is_word(k, "ORDER") || !is_word(k + 1, "BY")) continue;
        // The clause runs to LIMIT, OFFSET, VALUES or the end.
        std::size_t last = k + 1;
        int inner = 0;
        for (std::size_t j = k + 2; j < tokens.size(); ++j) {
            if (inner == 0 && (is_word(j, "LIMIT") || is_word(j, "OFFSET") || is_word(j, "VALUES")))
                break;
            if (opens(j)) ++inner;
            if (closes(j)) --inner;
            last = j;
        }
        const std::size_t begin = tokens[k].begin, end = tokens[last].end;
        return apply_edits(query, {{begin, end, line_breaks(query, begin, end)}});
    }
    return query;
}

std::string where_clause_as_ask(const std::string& query) {
    const std::vector<SparqlToken> tokens = tokenize_sparql(query);
    auto text = [&](std::size_t k) { return token_text(query, tokens[k]); };
    auto word_is = [&](std::size_t k, std::string_view w) { return is_keyword(query, tokens[k], w); };
    std::size_t k = 0;
    while (k < tokens.size() && !word_is(k, "SELECT")) {
        if (word_is(k, "ASK") || word_is(k, "CONSTRUCT") || word_is(k, "DESCRIBE")) return {};
        ++k;
    }
    const std::size_t select = k;
    while (k < tokens.size() && !(tokens[k].kind == Kind::Punct && text(k) == "{")) ++k;
    if (k >= tokens.size()) return {};
    const std::size_t open = k;
    int depth = 0;
    for (; k < tokens.size(); ++k) {
        if (tokens[k].kind != Kind::Punct) continue;
        if (text(k) == "{") ++depth;
        if (text(k) == "}" && --depth == 0) break;
    }
    if (k >= tokens.size()) return {};
    const std::size_t close = k;
    std::string ask = query.substr(0, select < tokens.size() ? tokens[select].begin : 0);
    ask += "ASK ";
    ask += query.substr(tokens[open].begin, tokens[close].end - tokens[open].begin);
    for (k = close + 1; k < tokens.size(); ++k) {
        if (word_is(k, "VALUES")) {
            ask += "\n";
            ask += query.substr(tokens[k].begin);
            break;
        }
    }
    return ask;
}

}  // namespace geotex::detail
