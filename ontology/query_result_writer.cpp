// Writers of a SPARQL result: an aligned text table, CSV and the SPARQL 1.1 results JSON. Cells
// are decoded from the N-Triples terms that run_sparql keeps (QueryResult::terms).
#include <cstring>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "common/detail/csv.hpp"
#include "common/detail/text.hpp"
#include "ontology/rdf_lexical.hpp"
#include "ontology/sparql.hpp"

namespace geotex {

namespace {

constexpr const char* kXsd = "http://www.w3.org/2001/XMLSchema#";

/// One cell of a result, decoded.
struct Term {
    enum class Kind { Unbound, Iri, Blank, Literal };
    Kind kind = Kind::Unbound;
    std::string value;  // IRI, blank node label or lexical form
    std::string language;
    std::string datatype;
};

/// Reads an N-Triples term as written by this file. Text that is not a term (a QueryResult
/// filled by hand) is taken as a plain literal.
Term parse_nt_term(std::string_view nt) {
    Term term;
    if (nt.empty()) return term;
    if (nt.size() >= 2 && nt.front() == '<' && nt.back() == '>') {
        term.kind = Term::Kind::Iri;
        term.value = rdf_detail::unescape_string_body(nt.substr(1, nt.size() - 2));
        return term;
    }
    if (nt.size() >= 2 && nt.substr(0, 2) == "_:") {
        term.kind = Term::Kind::Blank;
        term.value = std::string(nt.substr(2));
        return term;
    }
    term.kind = Term::Kind::Literal;
    if (nt.front() == '"') {
        std::size_t end = 1;
        while (end < nt.size() && nt[end] != '"') end += nt[end] == '\\' ? 2 : 1;
        if (end < nt.size()) {
            term.value = rdf_detail::unescape_string_body(nt.substr(1, end - 1));
            const std::string_view rest = nt.substr(end + 1);
            if (!rest.empty() && rest.front() == '@') {
                term.language = std::string(rest.substr(1));
            } else if (rest.size() >= 4 && rest.substr(0, 3) == "^^<" && rest.back() == '>') {
                term.datatype = rdf_detail::unescape_string_body(rest.substr(3, rest.size() - 4));
            }
            return term;
        }
    }
    term.value = std::string(nt);
    return term;
}

/// The decoded cell (r, c): from `terms` when the result has them, else from `rows`
/// ("" unbound, "<iri>", "_:label", anything else a plain literal).
Term cell_term(const QueryResult& result, std::size_t r, std::size_t c) {
    if (r < result.terms.size() && c < result.terms[r].size())
        return parse_nt_term(result.terms[r][c]);
    Term term;
    if (r >= result.rows.size() || c >= result.rows[r].size() || result.rows[r][c].empty())
        return term;
    const std::string& cell = result.rows[r][c];
    if (cell.size() >= 2 && cell.front() == '<' && cell.back() == '>') {
        term.kind = Term::Kind::Iri;
        term.value = cell.substr(1, cell.size() - 2);
    } else if (cell.compare(0, 2, "_:") == 0) {
        term.kind = Term::Kind::Blank;
        term.value = cell.substr(2);
    } else {
        term.kind = Term::Kind::Literal;
        term.value = cell;
    }
    return term;
}

bool is_numeric_datatype(const std::string& datatype) {
    if (datatype.compare(0, std::strlen(kXsd), kXsd) != 0) return false;
    static const std::unordered_set<std::string> numeric = {"integer",
                                                            "decimal",
                                                            "double",
                                                            "float",
                                                            "int",
                                                            "long",
                                                            "short",
                                                            "byte",
                                                            "nonNegativeInteger",
                                                            "positiveInteger",
                                                            "nonPositiveInteger",
                                                            "negativeInteger",
                                                            "unsignedLong",
                                                            "unsignedInt",
                                                            "unsignedShort",
                                                            "unsignedByte"};
    return numeric.count(datatype.substr(std::strlen(kXsd))) > 0;
}

/// Decodes one UTF-8 sequence at `i` (advancing it); an ill-formed byte gives U+FFFD.
char32_t next_code_point(std::string_view s, std::size_t& i) {
    char32_t cp = 0;
    const std::size_t len = detail::utf8_decode(s, i, cp);
    i += len == 0 ? 1 : len;
    return len == 0 ? char32_t{0xFFFD} : cp;
}

/// Columns a code point takes in a terminal: 0 for combining marks and zero-width
/// characters, 2 for East Asian wide and fullwidth characters and emoji, else 1.
int code_point_width(char32_t cp) {
    struct Range {
        char32_t first, last;
    };
    static const Range zero[] = {
        {0x0300, 0x036F}, {0x0483, 0x0489}, {0x0591, 0x05BD}, {0x0610, 0x061A}, {0x064B, 0x065F},
        {0x1AB0, 0x1AFF}, {0x1DC0, 0x1DFF}, {0x200B, 0x200F}, {0x2028, 0x202E}, {0x2060, 0x2064},
        {0x20D0, 0x20FF}, {0xFE00, 0xFE0F}, {0xFE20, 0xFE2F}, {0xFEFF, 0xFEFF}, {0xE0100, 0xE01EF}};
    static const Range wide[] = {{0x1100, 0x115F},   {0x2E80, 0x303E},   {0x3041, 0x33FF},
                                 {0x3400, 0x4DBF},   {0x4E00, 0x9FFF},   {0xA000, 0xA4CF},
                                 {0xAC00, 0xD7A3},   {0xF900, 0xFAFF},   {0xFE30, 0xFE4F},
                                 {0xFF00, 0xFF60},   {0xFFE0, 0xFFE6},   {0x1F300, 0x1F64F},
                                 {0x1F900, 0x1F9FF}, {0x20000, 0x2FFFD}, {0x30000, 0x3FFFD}};
    for (const Range& r : zero)
        if (cp >= r.first && cp <= r.last) return 0;
    for (const Range& r : wide)
        if (cp >= r.first && cp <= r.last) return 2;
    return 1;
}

std::size_t display_width(std::string_view s) {
    std::size_t width = 0;
    for (std::size_t i = 0; i < s.size();)
        width += static_cast<std::size_t>(code_point_width(next_code_point(s, i)));
    return width;
}

/// A cell as shown in the table: control characters visible as escapes, so that a value
/// with a newline stays on its line.
std::string table_text(std::string_view s) {
    std::string out;
    for (char ch : s) {
        const auto c = static_cast<unsigned char>(ch);
        if (c == '\n')
            out += "\\n";
        else if (c == '\r')
            out += "\\r";
        else if (c == '\t')
            out += "\\t";
        else if (c < 0x20 || c == 0x7F)
            detail::append_u_escape(out, c);
        else
            out += ch;
    }
    return out;
}

void write_table(std::ostream& out, const QueryResult& result) {
    if (result.is_boolean) {
        out << (result.boolean_value ? "true" : "false") << '\n';
        return;
    }
    const std::size_t num_columns = result.variables.size();
    const std::size_t num_rows = result.rows.size();
    std::vector<std::vector<std::string>> cells(num_rows, std::vector<std::string>(num_columns));
    std::vector<std::vector<bool>> right(num_rows, std::vector<bool>(num_columns, false));
    std::vector<std::size_t> width(num_columns);
    for (std::size_t c = 0; c < num_columns; ++c) width[c] = display_width(result.variables[c]);
    for (std::size_t r = 0; r < num_rows; ++r) {
        for (std::size_t c = 0; c < num_columns; ++c) {
            const Term term = cell_term(result, r, c);
            std::string text;
            switch (term.kind) {
                case Term::Kind::Unbound:
                    break;
                case Term::Kind::Iri:
                    text = "<" + term.value + ">";
                    break;
                case Term::Kind::Blank:
                    text = "_:" + term.value;
                    break;
                case Term::Kind::Literal:
                    text = term.value;
                    right[r][c] = is_numeric_datatype(term.datatype);
                    break;
            }
            cells[r][c] = table_text(text);
            width[c] = std::max(width[c], display_width(cells[r][c]));
        }
    }
    auto write_line = [&](const std::vector<std::string>& line,
                          const std::vector<bool>* align_right) {
        std::string text;
        for (std::size_t c = 0; c < num_columns; ++c) {
            if (c > 0) text += " | ";
            const std::size_t pad = width[c] - display_width(line[c]);
            const bool to_right = align_right && (*align_right)[c];
            if (to_right) text.append(pad, ' ');
            text += line[c];
            if (!to_right && c + 1 < num_columns) text.append(pad, ' ');
        }
        while (!text.empty() && text.back() == ' ') text.pop_back();
        out << text << '\n';
    };
    write_line(result.variables, nullptr);
    std::string rule;
    for (std::size_t c = 0; c < num_columns; ++c) {
        if (c > 0) rule += "-+-";
        rule.append(width[c], '-');
    }
    out << rule << '\n';
    for (std::size_t r = 0; r < num_rows; ++r) {
        const std::vector<bool> align = right[r];
        write_line(cells[r], &align);
    }
    out << '(' << num_rows << (num_rows == 1 ? " row)" : " rows)") << '\n';
}

/// A CSV field; a U+0000 of the value is written as the six characters \u0000, as in the
/// table: a NUL byte cuts the text in most programs that read CSV (C strings), and the JSON
/// results hold the exact value.
void write_csv_field(std::ostream& out, const std::string& field) {
    if (field.find('\0') == std::string::npos) {
        out << detail::csv_field(field);
        return;
    }
    std::string visible;
    for (char ch : field) {
        if (ch == '\0')
            visible += "\\u0000";
        else
            visible += ch;
    }
    out << detail::csv_field(visible);
}

/// SPARQL 1.1 CSV results: IRIs bare, blank nodes as _:label, literals as their lexical
/// form; RFC 4180 quoting and CRLF line ends. An ASK answer is written `_askResult` then
/// `true` or `false`, as Jena does (the CSV format does not cover ASK).
void write_csv(std::ostream& out, const QueryResult& result) {
    if (result.is_boolean) {
        out << "_askResult\r\n" << (result.boolean_value ? "true" : "false") << "\r\n";
        return;
    }
    for (std::size_t c = 0; c < result.variables.size(); ++c) {
        if (c > 0) out << ',';
        write_csv_field(out, result.variables[c]);
    }
    out << "\r\n";
    for (std::size_t r = 0; r < result.rows.size(); ++r) {
        for (std::size_t c = 0; c < result.variables.size(); ++c) {
            if (c > 0) out << ',';
            const Term term = cell_term(result, r, c);
            write_csv_field(out, term.kind == Term::Kind::Blank ? "_:" + term.value : term.value);
        }
        out << "\r\n";
    }
}

/// SPARQL 1.1 Query Results JSON Format (W3C Recommendation, 2013). nlohmann_json does the
/// escaping; an invalid UTF-8 byte becomes U+FFFD so the output is always valid JSON.
void write_json(std::ostream& out, const QueryResult& result) {
    using Json = nlohmann::ordered_json;
    Json doc;
    if (result.is_boolean) {
        doc["head"] = Json::object();
        doc["boolean"] = result.boolean_value;
    } else {
        doc["head"]["vars"] = result.variables;
        Json bindings = Json::array();
        for (std::size_t r = 0; r < result.rows.size(); ++r) {
            Json row = Json::object();
            for (std::size_t c = 0; c < result.variables.size(); ++c) {
                const Term term = cell_term(result, r, c);
                if (term.kind == Term::Kind::Unbound) continue;
                Json cell;
                cell["type"] = term.kind == Term::Kind::Iri     ? "uri"
                               : term.kind == Term::Kind::Blank ? "bnode"
                                                                : "literal";
                cell["value"] = term.value;
                if (!term.language.empty()) cell["xml:lang"] = term.language;
                if (!term.datatype.empty()) cell["datatype"] = term.datatype;
                row[result.variables[c]] = std::move(cell);
            }
            bindings.push_back(std::move(row));
        }
        doc["results"]["bindings"] = std::move(bindings);
    }
    out << doc.dump(2, ' ', false, Json::error_handler_t::replace) << '\n';
}

}  // namespace

void write_query_result(std::ostream& out, const QueryResult& result, ResultFormat format) {
    switch (format) {
        case ResultFormat::Table:
            write_table(out, result);
            break;
        case ResultFormat::Csv:
            write_csv(out, result);
            break;
        case ResultFormat::Json:
            write_json(out, result);
            break;
    }
}

}  // namespace geotex
