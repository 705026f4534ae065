#include "ontology/detail/sparql_aggregates.hpp"

#include <algorithm>
#include <string_view>

#include "common/detail/text.hpp"
#include "ontology/detail/sparql_tokens.hpp"
#include "ontology/rdf_lexical.hpp"

namespace geotex::detail {

using Kind = SparqlToken::Kind;

namespace {

/// The text of a SPARQL string token (quotes removed, escapes resolved).
std::string unescape_string(std::string_view token) {
    const bool triple = token.size() >= 6 && token[1] == token[0] && token[2] == token[0];
    const std::size_t quote = triple ? 3 : 1;
    if (token.size() < 2 * quote) return {};
    return rdf_detail::unescape_string_body(token.substr(quote, token.size() - 2 * quote));
}

}  // namespace

std::string rewrite_aggregates(const std::string& query,
                               std::vector<ConcatColumn>* concat_columns) {
    const std::vector<SparqlToken> t = tokenize_sparql(query);
    auto text = [&](std::size_t k) { return token_text(query, t[k]); };
    auto word = [&](std::size_t k, std::string_view w) {
        return k < t.size() && is_keyword(query, t[k], w);
    };
    auto punct = [&](std::size_t k, std::string_view p) {
        return k < t.size() && is_punct(query, t[k], p);
    };
    std::vector<TextEdit> edits;
    // The outermost SELECT clause and its ORDER BY, for the GROUP_CONCAT columns.
    std::size_t select = t.size(), where = t.size();
    for (std::size_t k = 0; k < t.size(); ++k) {
        if (select == t.size() && word(k, "SELECT")) select = k;
        if (select != t.size() && punct(k, "{")) {
            where = k;
            break;
        }
    }
    std::size_t order_by = t.size();
    for (std::size_t k = where; k < t.size(); ++k)
        if (word(k, "ORDER")) order_by = k;

    for (std::size_t k = 0; k + 3 < t.size(); ++k) {
        // COUNT ( ?x )
        if (word(k, "COUNT") && punct(k + 1, "(") && t[k + 2].kind == Kind::Variable &&
            punct(k + 3, ")")) {
            const std::string v(text(k + 2));
            edits.push_back({t[k].begin, t[k + 3].end, "SUM(IF(BOUND(" + v + "), 1, 0))"});
            k += 3;
            continue;
        }
        // ( GROUP_CONCAT ( expr ; SEPARATOR = "s" ) AS ?v ), in the outermost SELECT clause
        if (!concat_columns || k <= select || k >= where || !punct(k, "(") ||
            !word(k + 1, "GROUP_CONCAT") || !punct(k + 2, "(") || word(k + 3, "DISTINCT"))
            continue;
        std::size_t j = k + 3;
        int depth = 0;
        while (j < where && !(depth == 0 && (punct(j, ";") || punct(j, ")")))) {
            if (punct(j, "(")) ++depth;
            if (punct(j, ")")) --depth;
            ++j;
        }
        if (j == k + 3 || !punct(j, ";") || !word(j + 1, "SEPARATOR") || !punct(j + 2, "=") ||
            j + 3 >= t.size() || t[j + 3].kind != Kind::String || !punct(j + 4, ")") ||
            !word(j + 5, "AS") || j + 6 >= t.size() || t[j + 6].kind != Kind::Variable ||
            !punct(j + 7, ")"))
            continue;
        const std::string variable(text(j + 6).substr(1));
        // Sorting by the column would sort by its encoded text: left to Rasqal then.
        bool sorted_by = false;
        for (std::size_t m = order_by; m < t.size(); ++m)
            sorted_by = sorted_by || (t[m].kind == Kind::Variable && text(m).substr(1) == variable);
        if (sorted_by) continue;
        const std::string expr = query.substr(t[k + 3].begin, t[j - 1].end - t[k + 3].begin);
        edits.push_back({t[k + 2].begin, t[j + 4].end,
                         "(IF(STR(" + expr + ") = \"\", \"%\", ENCODE_FOR_URI(STR(" + expr +
                             "))))" + line_breaks(query, t[k + 2].begin, t[j + 4].end)});
        concat_columns->push_back({variable, unescape_string(text(j + 3))});
        k = j + 7;
    }
    return edits.empty() ? query : apply_edits(query, std::move(edits));
}

std::string join_concat_parts(const std::string& joined, const std::string& separator) {
    std::string out;
    std::size_t start = 0;
    while (true) {
        const std::size_t space = joined.find(' ', start);
        const std::string_view part = std::string_view(joined).substr(
            start, space == std::string::npos ? std::string::npos : space - start);
        if (start > 0) out += separator;
        // A lone "%" (never an encoded text) stands for "" (rewrite_aggregates).
        for (std::size_t i = part == "%" ? 1 : 0; i < part.size(); ++i) {
            auto hex = [](char c) {
                return c >= '0' && c <= '9'   ? c - '0'
                       : c >= 'A' && c <= 'F' ? c - 'A' + 10
                       : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                              : -1;
            };
            if (part[i] == '%' && i + 2 < part.size() && hex(part[i + 1]) >= 0 &&
                hex(part[i + 2]) >= 0) {
                out += static_cast<char>(hex(part[i + 1]) * 16 + hex(part[i + 2]));
                i += 2;
            } else {
                out += part[i];
            }
        }
        if (space == std::string::npos) break;
        start = space + 1;
    }
    return out;
}

}  // namespace geotex::detail
