#include "ontology/detail/sparql_clauses.hpp"

#include <algorithm>
#include <string_view>
#include <vector>

#include "ontology/detail/sparql_tokens.hpp"

namespace geotex::detail {

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

namespace {

/// Where the parts of the outermost SELECT are, as token indices.
struct SelectParts {
    std::size_t select = 0;  ///< the SELECT keyword
    std::size_t open = 0;    ///< the '{' that opens the WHERE clause
    std::size_t close = 0;   ///< the '}' that closes it
    std::size_t values = 0;  ///< a trailing VALUES keyword, or the number of tokens
};

/// The parts of the outermost SELECT of `query`; false when it is no SELECT with a WHERE
/// clause (an ASK, CONSTRUCT or DESCRIBE, or an unclosed brace).
bool find_select(const std::string& query, const std::vector<SparqlToken>& tokens,
                 SelectParts& parts) {
    auto word_is = [&](std::size_t k, std::string_view w) {
        return is_keyword(query, tokens[k], w);
    };
    std::size_t k = 0;
    while (k < tokens.size() && !word_is(k, "SELECT")) {
        if (word_is(k, "ASK") || word_is(k, "CONSTRUCT") || word_is(k, "DESCRIBE")) return false;
        ++k;
    }
    parts.select = k;
    while (k < tokens.size() && !is_punct(query, tokens[k], "{")) ++k;
    if (k >= tokens.size()) return false;
    parts.open = k;
    int depth = 0;
    for (; k < tokens.size(); ++k) {
        if (is_punct(query, tokens[k], "{")) ++depth;
        if (is_punct(query, tokens[k], "}") && --depth == 0) break;
    }
    if (k >= tokens.size()) return false;
    parts.close = k;
    for (parts.values = k + 1; parts.values < tokens.size(); ++parts.values)
        if (word_is(parts.values, "VALUES")) break;
    return true;
}

}  // namespace

std::string where_clause_as_ask(const std::string& query) {
    const std::vector<SparqlToken> tokens = tokenize_sparql(query);
    SelectParts p;
    if (!find_select(query, tokens, p)) return {};
    std::string ask = query.substr(0, p.select < tokens.size() ? tokens[p.select].begin : 0);
    ask += "ASK ";
    ask += query.substr(tokens[p.open].begin, tokens[p.close].end - tokens[p.open].begin);
    if (p.values < tokens.size()) {
        ask += "\n";
        ask += query.substr(tokens[p.values].begin);
    }
    return ask;
}

std::string ungrouped_select(const std::string& query, const std::vector<std::string>& variables) {
    const std::vector<SparqlToken> tokens = tokenize_sparql(query);
    SelectParts p;
    if (!find_select(query, tokens, p) || p.select >= p.open) return {};
    std::string head = "SELECT";
    for (const std::string& v : variables) head += " ?" + v;
    head += ' ';
    // From SELECT to the WHERE keyword or, without one, to the brace.
    std::size_t head_end = tokens[p.open].begin;
    if (p.open > p.select + 1 && is_keyword(query, tokens[p.open - 1], "WHERE"))
        head_end = tokens[p.open - 1].begin;
    std::vector<TextEdit> edits;
    const std::size_t begin = tokens[p.select].begin;
    edits.push_back({begin, head_end, head + line_breaks(query, begin, head_end)});
    if (p.values > p.close + 1) {
        const std::size_t from = tokens[p.close + 1].begin, to = tokens[p.values - 1].end;
        edits.push_back({from, to, line_breaks(query, from, to)});
    }
    return apply_edits(query, std::move(edits));
}

}  // namespace geotex::detail
