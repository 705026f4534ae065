// SPARQL over geotex output, embedded: Raptor2 reads the data files, Rasqal 0.9.33 runs the
// query, and the results are written as a text table, CSV or SPARQL 1.1 results JSON.

#include "ontology/sparql.hpp"

#include <rasqal.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "geometry/errors.hpp"

namespace geotex {

namespace {

// ---------------------------------------------------------------------------------------
// Owning handles for the C objects of Raptor and Rasqal.

template <auto Free>
struct Deleter {
    template <class T>
    void operator()(T* p) const {
        if (p) Free(p);
    }
};

using RaptorWorld = std::unique_ptr<raptor_world, Deleter<raptor_free_world>>;
using RaptorParser = std::unique_ptr<raptor_parser, Deleter<raptor_free_parser>>;
using RaptorUri = std::unique_ptr<raptor_uri, Deleter<raptor_free_uri>>;
using RaptorIostream = std::unique_ptr<raptor_iostream, Deleter<raptor_free_iostream>>;
using RasqalWorld = std::unique_ptr<rasqal_world, Deleter<rasqal_free_world>>;
using RasqalQuery = std::unique_ptr<rasqal_query, Deleter<rasqal_free_query>>;
using RasqalResults = std::unique_ptr<rasqal_query_results, Deleter<rasqal_free_query_results>>;
using RasqalDataGraph = std::unique_ptr<rasqal_data_graph, Deleter<rasqal_free_data_graph>>;

constexpr const char* kXsd = "http://www.w3.org/2001/XMLSchema#";

// ---------------------------------------------------------------------------------------
// Messages: Raptor and Rasqal report problems through a log handler; they are kept here
// (the library prints nothing) and turned into exceptions by the caller.

struct LogEntry {
    raptor_log_level level = RAPTOR_LOG_LEVEL_NONE;
    std::string text;
    long line = 0;    // 1-based, 0 = unknown
    long column = 0;  // 1-based, 0 = unknown
};

struct MessageLog {
    std::vector<LogEntry> entries;

    /// The first error logged at or after index `from`, or nullptr.
    const LogEntry* first_error(std::size_t from) const {
        for (std::size_t i = from; i < entries.size(); ++i)
            if (entries[i].level >= RAPTOR_LOG_LEVEL_ERROR) return &entries[i];
        return nullptr;
    }
};

void on_log_message(void* user_data, raptor_log_message* message) noexcept {
    try {
        LogEntry entry;
        entry.level = message->level;
        entry.text = message->text ? message->text : "";
        while (!entry.text.empty() && (entry.text.back() == '\n' || entry.text.back() == ' '))
            entry.text.pop_back();
        if (message->locator) {
            entry.line = message->locator->line > 0 ? message->locator->line : 0;
            entry.column = message->locator->column > 0 ? message->locator->column : 0;
        }
        static_cast<MessageLog*>(user_data)->entries.push_back(std::move(entry));
    } catch (...) {
        // Out of memory while keeping a message: the failing call still returns an error,
        // which the caller reports without this text.
    }
}

// ---------------------------------------------------------------------------------------
// N-Triples terms (written here for the data handed to Rasqal and for QueryResult::terms,
// read back by the result writers).

void append_hex_escape(std::string& out, unsigned code) {
    static const char* const digits = "0123456789ABCDEF";
    out += "\\u00";
    out += digits[(code >> 4) & 0xF];
    out += digits[code & 0xF];
}

/// Escapes a literal's lexical form the canonical N-Triples way: \" \\ \n \r, and \u00XX
/// for the other control characters (UTF-8 passes through).
void append_escaped_literal(std::string& out, std::string_view text) {
    for (char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\r':
                out += "\\r";
                break;
            default:
                if (c < 0x20 || c == 0x7F)
                    append_hex_escape(out, c);
                else
                    out += ch;
        }
    }
}

/// Escapes the characters that an N-Triples IRIREF cannot hold as \u00XX.
void append_escaped_iri(std::string& out, std::string_view iri) {
    static const std::string_view forbidden = "<>\"{}|^`\\";
    for (char ch : iri) {
        const auto c = static_cast<unsigned char>(ch);
        if (c <= 0x20 || c == 0x7F || forbidden.find(ch) != std::string_view::npos)
            append_hex_escape(out, c);
        else
            out += ch;
    }
}

std::string nt_iri(std::string_view iri) {
    std::string out = "<";
    append_escaped_iri(out, iri);
    out += '>';
    return out;
}

std::string nt_literal(std::string_view lexical, std::string_view language,
                       std::string_view datatype) {
    std::string out = "\"";
    append_escaped_literal(out, lexical);
    out += '"';
    if (!language.empty()) {
        out += '@';
        out += language;
    } else if (!datatype.empty()) {
        out += "^^";
        out += nt_iri(datatype);
    }
    return out;
}

/// Appends one code point as UTF-8 (U+FFFD for values that are not scalar values).
void append_utf8(std::string& out, std::uint32_t cp) {
    if (cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) cp = 0xFFFD;
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

/// Undoes N-Triples escapes (\t \b \n \r \f \" \' \\ \uXXXX \UXXXXXXXX).
std::string nt_unescape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '\\' || i + 1 >= text.size()) {
            out += text[i];
            continue;
        }
        const char e = text[++i];
        switch (e) {
            case 't':
                out += '\t';
                break;
            case 'b':
                out += '\b';
                break;
            case 'n':
                out += '\n';
                break;
            case 'r':
                out += '\r';
                break;
            case 'f':
                out += '\f';
                break;
            case 'u':
            case 'U': {
                const std::size_t n = e == 'u' ? 4 : 8;
                std::uint32_t cp = 0;
                bool ok = i + n < text.size();  // the digits are text[i + 1 .. i + n]
                for (std::size_t k = 1; ok && k <= n; ++k) {
                    const char h = text[i + k];
                    int v = -1;
                    if (h >= '0' && h <= '9') v = h - '0';
                    if (h >= 'a' && h <= 'f') v = h - 'a' + 10;
                    if (h >= 'A' && h <= 'F') v = h - 'A' + 10;
                    if (v < 0) ok = false;
                    cp = cp * 16 + static_cast<std::uint32_t>(v < 0 ? 0 : v);
                }
                if (ok) {
                    append_utf8(out, cp);
                    i += n;
                } else {
                    out += '\\';
                    out += e;
                }
                break;
            }
            default:
                out += e;  // \" \' \\ and anything unknown: the character itself
        }
    }
    return out;
}

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
        term.value = nt_unescape(nt.substr(1, nt.size() - 2));
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
            term.value = nt_unescape(nt.substr(1, end - 1));
            const std::string_view rest = nt.substr(end + 1);
            if (!rest.empty() && rest.front() == '@') {
                term.language = std::string(rest.substr(1));
            } else if (rest.size() >= 4 && rest.substr(0, 3) == "^^<" && rest.back() == '>') {
                term.datatype = nt_unescape(rest.substr(3, rest.size() - 4));
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

// ---------------------------------------------------------------------------------------
// Data: every file is parsed with Raptor into one N-Triples text without duplicate triples.
// Rasqal's own loader keeps every parsed triple, so a triple written twice (in one file, or
// in two files, as the dictionary concepts of two annotation files are) would match twice;
// the SPARQL dataset is a set, so the duplicates go here.

struct GraphBuilder {
    std::string ntriples;                  // the deduplicated union, in reading order
    std::unordered_set<std::string> seen;  // its lines
    std::unordered_map<std::string, std::string> blank_labels;  // of the current file
    std::size_t file_index = 0;
    std::size_t num_blanks = 0;
    std::string line;            // scratch
    std::exception_ptr failure;  // thrown inside the statement handler
    raptor_parser* parser = nullptr;

    void append_term(const raptor_term* term) {
        switch (term->type) {
            case RAPTOR_TERM_TYPE_URI: {
                std::size_t len = 0;
                const unsigned char* s = raptor_uri_as_counted_string(term->value.uri, &len);
                line += '<';
                append_escaped_iri(line, std::string_view(reinterpret_cast<const char*>(s), len));
                line += '>';
                break;
            }
            case RAPTOR_TERM_TYPE_BLANK: {
                // Blank node labels are local to their file: renumber them so that `_:b1`
                // of two files stays two nodes.
                const std::string label(reinterpret_cast<const char*>(term->value.blank.string),
                                        term->value.blank.string_len);
                auto found = blank_labels.find(label);
                if (found == blank_labels.end()) {
                    found = blank_labels
                                .emplace(label, "f" + std::to_string(file_index) + "b" +
                                                    std::to_string(num_blanks++))
                                .first;
                }
                line += "_:";
                line += found->second;
                break;
            }
            case RAPTOR_TERM_TYPE_LITERAL: {
                const raptor_term_literal_value& lit = term->value.literal;
                line += '"';
                append_escaped_literal(
                    line,
                    std::string_view(reinterpret_cast<const char*>(lit.string), lit.string_len));
                line += '"';
                if (lit.language && lit.language_len > 0) {
                    line += '@';
                    line.append(reinterpret_cast<const char*>(lit.language), lit.language_len);
                } else if (lit.datatype) {
                    std::size_t len = 0;
                    const unsigned char* s = raptor_uri_as_counted_string(lit.datatype, &len);
                    line += "^^<";
                    append_escaped_iri(line,
                                       std::string_view(reinterpret_cast<const char*>(s), len));
                    line += '>';
                }
                break;
            }
            default:
                line += "_:unknown";
        }
    }

    void add(const raptor_statement* st) {
        line.clear();
        append_term(st->subject);
        line += ' ';
        append_term(st->predicate);
        line += ' ';
        append_term(st->object);
        line += " .\n";
        if (seen.insert(line).second) ntriples += line;
    }
};

void on_statement(void* user_data, raptor_statement* statement) noexcept {
    auto* builder = static_cast<GraphBuilder*>(user_data);
    if (builder->failure) return;
    try {
        builder->add(statement);
    } catch (...) {
        builder->failure = std::current_exception();
        raptor_parser_parse_abort(builder->parser);
    }
}

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) {
        return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    });
    return ext;
}

/// How to read a data file: the Raptor parser and the syntax's name for messages.
struct Syntax {
    const char* parser;
    const char* name;
};

/// The syntax of a data file, from its name's extension. N-Triples is read with the Turtle
/// parser (N-Triples is a subset of Turtle): Raptor 2.0.15's N-Triples parser leaks URIs.
Syntax syntax_for(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".ttl" || ext == ".turtle") return {"turtle", "Turtle"};
    if (ext == ".nt") return {"turtle", "N-Triples"};
    if (ext == ".nq") return {"nquads", "N-Quads"};
    if (ext == ".rdf" || ext == ".owl" || ext == ".xml") return {"rdfxml", "RDF/XML"};
    throw InvalidInput(
        "cannot tell the RDF syntax of a data file from its name: use .ttl "
        "(Turtle), .nt (N-Triples), .nq (N-Quads) or .rdf (RDF/XML)",
        path);
}

std::string read_data_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw IoError("cannot read RDF data file: it is a directory", path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(std::string("cannot open RDF data file: ") + std::strerror(errno), path);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad())
        throw IoError(std::string("cannot read RDF data file: ") + std::strerror(errno), path);
    return bytes;
}

void load_data_file(raptor_world* raptor, MessageLog& log, GraphBuilder& builder,
                    const std::string& path) {
    const std::string bytes = read_data_file(path);
    const Syntax syntax = syntax_for(path);

    // Relative IRIs in the file resolve against the file's own URI, as with roqet -D.
    std::error_code ec;
    const std::string absolute = std::filesystem::absolute(path, ec).string();
    unsigned char* uri_string =
        raptor_uri_filename_to_uri_string(ec ? path.c_str() : absolute.c_str());
    if (!uri_string) throw IoError("cannot make a file URI for the RDF data file", path);
    RaptorUri base(raptor_new_uri(raptor, uri_string));
    raptor_free_memory(uri_string);

    RaptorParser parser(raptor_new_parser(raptor, syntax.parser));
    if (!base || !parser) throw IoError("Raptor could not start a parser (out of memory?)", path);
    raptor_parser_set_option(parser.get(), RAPTOR_OPTION_NO_NET, nullptr, 1);

    builder.blank_labels.clear();
    builder.parser = parser.get();
    raptor_parser_set_statement_handler(parser.get(), &builder, on_statement);

    const std::size_t mark = log.entries.size();
    int rc = raptor_parser_parse_start(parser.get(), base.get());
    if (rc == 0)
        rc = raptor_parser_parse_chunk(
            parser.get(), reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), 1);
    builder.parser = nullptr;
    ++builder.file_index;
    if (builder.failure) std::rethrow_exception(builder.failure);
    if (const LogEntry* error = log.first_error(mark))
        throw ParseError(std::string("invalid ") + syntax.name + ": " + error->text, path,
                         error->line, error->column);
    if (rc != 0)
        throw ParseError(std::string("invalid ") + syntax.name + " (no reason given)", path);
}

// ---------------------------------------------------------------------------------------
// The query text: checks for what Rasqal 0.9.33 gets wrong without saying so.

/// Throws InvalidInput at the first one-variable `VALUES ?x { ... }` block: Rasqal 0.9.33
/// returns only the first value's rows for it inside a pattern and crashes on it after the
/// WHERE clause. Strings, comments and IRIs are skipped.
void check_values_form(const std::string& query) {
    auto is_word = [](char c) {
        return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
               c == '_' || c == ':' || c == '?' || c == '$' ||
               static_cast<unsigned char>(c) >= 0x80;
    };
    long line = 1;
    std::size_t line_start = 0;
    const std::size_t n = query.size();
    std::size_t i = 0;
    auto newline_at = [&](std::size_t k) {
        if (query[k] == '\n') {
            ++line;
            line_start = k + 1;
        }
    };
    while (i < n) {
        const char c = query[i];
        if (c == '\n') {
            newline_at(i);
            ++i;
        } else if (c == '#') {
            while (i < n && query[i] != '\n') ++i;
        } else if (c == '"' || c == '\'') {
            const bool triple = i + 2 < n && query[i + 1] == c && query[i + 2] == c;
            const std::size_t quote = triple ? 3 : 1;
            i += quote;
            while (i < n) {
                if (query[i] == '\\') {
                    i += 2;
                    continue;
                }
                if (query[i] == c &&
                    (!triple || (i + 2 < n && query[i + 1] == c && query[i + 2] == c)))
                    break;
                newline_at(i);
                ++i;
            }
            i += quote;
        } else if (c == '<') {
            // An IRI reference, or the less-than operator: an IRI has no space or quote.
            std::size_t k = i + 1;
            while (k < n && query[k] != '>' && std::strchr(" \t\r\n<\"{}|^`", query[k]) == nullptr)
                ++k;
            i = (k < n && query[k] == '>') ? k + 1 : i + 1;
        } else if ((c == 'v' || c == 'V') && (i == 0 || !is_word(query[i - 1])) && i + 6 <= n &&
                   (i + 6 == n || !is_word(query[i + 6]))) {
            std::string word = query.substr(i, 6);
            std::transform(word.begin(), word.end(), word.begin(),
                           [](unsigned char ch) { return static_cast<char>(ch & ~0x20); });
            const long column = static_cast<long>(i - line_start) + 1;
            const long at_line = line;
            i += 6;
            if (word != "VALUES") continue;
            std::size_t k = i;
            while (k < n) {
                if (query[k] == '#') {
                    while (k < n && query[k] != '\n') ++k;
                } else if (query[k] == ' ' || query[k] == '\t' || query[k] == '\r' ||
                           query[k] == '\n') {
                    ++k;
                } else {
                    break;
                }
            }
            if (k < n && (query[k] == '?' || query[k] == '$'))
                throw InvalidInput(
                    "Rasqal 0.9.33 returns wrong rows for (or crashes on) the "
                    "one-variable form `VALUES ?x { ... }`: write it "
                    "`VALUES (?x) { (...) (...) }`",
                    "", at_line, column);
        } else {
            ++i;
        }
    }
}

bool mentions_minus(const std::string& query) {
    std::string upper = query;
    std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char ch) {
        return static_cast<char>(ch >= 'a' && ch <= 'z' ? ch - 32 : ch);
    });
    return upper.find("MINUS") != std::string::npos;
}

// ---------------------------------------------------------------------------------------
// Results

std::string uri_text(raptor_uri* uri) {
    std::size_t len = 0;
    const unsigned char* s = raptor_uri_as_counted_string(uri, &len);
    return s ? std::string(reinterpret_cast<const char*>(s), len) : std::string();
}

/// The (row, term) pair of one bound value.
std::pair<std::string, std::string> convert_value(rasqal_literal* value) {
    if (!value) return {std::string(), std::string()};
    if (value->type == RASQAL_LITERAL_URI) {
        const std::string iri = uri_text(value->value.uri);
        return {"<" + iri + ">", nt_iri(iri)};
    }
    if (value->type == RASQAL_LITERAL_BLANK) {
        const std::string label(reinterpret_cast<const char*>(value->string), value->string_len);
        return {"_:" + label, "_:" + label};
    }
    std::size_t len = 0;
    int error = 0;
    const unsigned char* s = rasqal_literal_as_counted_string(value, &len, 0, &error);
    const std::string lexical =
        s ? std::string(reinterpret_cast<const char*>(s), len) : std::string();
    const std::string language = value->language ? value->language : "";
    std::string datatype;
    if (language.empty()) {
        if (raptor_uri* dt = rasqal_literal_datatype(value)) datatype = uri_text(dt);
    }
    return {lexical, nt_literal(lexical, language, datatype)};
}

}  // namespace

QueryResult run_sparql(const std::string& query, const std::vector<std::string>& data_files) {
    check_values_form(query);

    MessageLog log;
    RaptorWorld raptor(raptor_new_world());
    if (!raptor) throw InvalidInput("run_sparql: Raptor could not start (out of memory?)");
    raptor_world_set_log_handler(raptor.get(), &log, on_log_message);
    if (raptor_world_open(raptor.get()) != 0)
        throw InvalidInput("run_sparql: Raptor could not start");

    // Declared after `raptor`, so destroyed before it: Rasqal uses the Raptor world to the end.
    RasqalWorld world(rasqal_new_world());
    if (!world) throw InvalidInput("run_sparql: Rasqal could not start (out of memory?)");
    rasqal_world_set_raptor(world.get(), raptor.get());
    rasqal_world_set_log_handler(world.get(), &log, on_log_message);
    if (rasqal_world_open(world.get()) != 0)
        throw InvalidInput("run_sparql: Rasqal could not start");

    RasqalQuery q(rasqal_new_query(world.get(), "sparql11-query", nullptr));
    if (!q) throw InvalidInput("run_sparql: Rasqal has no SPARQL 1.1 query language");

    std::size_t mark = log.entries.size();
    if (rasqal_query_prepare(q.get(), reinterpret_cast<const unsigned char*>(query.c_str()),
                             nullptr) != 0) {
        const LogEntry* error = log.first_error(mark);
        throw ParseError("SPARQL: " + (error ? error->text : std::string("syntax error")), "",
                         error ? error->line : 0, error ? error->column : 0);
    }

    const rasqal_query_verb verb = rasqal_query_get_verb(q.get());
    if (verb != RASQAL_QUERY_VERB_SELECT && verb != RASQAL_QUERY_VERB_ASK) {
        const char* name = verb == RASQAL_QUERY_VERB_CONSTRUCT  ? "CONSTRUCT"
                           : verb == RASQAL_QUERY_VERB_DESCRIBE ? "DESCRIBE"
                                                                : "this kind of";
        throw InvalidInput(std::string("only SELECT and ASK queries can be run, not ") + name +
                           " queries");
    }
    if (rasqal_query_get_data_graph(q.get(), 0) != nullptr)
        throw InvalidInput(
            "FROM and FROM NAMED are not supported: give the data files to query "
            "instead (their union is the default graph)");

    GraphBuilder builder;
    for (const std::string& file : data_files) load_data_file(raptor.get(), log, builder, file);
    std::unordered_set<std::string>().swap(builder.seen);  // Rasqal keeps its own copy

    // The iostream reads `builder.ntriples` in place and must outlive the execution.
    RaptorIostream data(raptor_new_iostream_from_string(raptor.get(), builder.ntriples.data(),
                                                        builder.ntriples.size()));
    RaptorUri data_base(raptor_new_uri(
        raptor.get(), reinterpret_cast<const unsigned char*>("urn:geotex:query-data")));
    if (!data || !data_base) throw InvalidInput("run_sparql: out of memory");
    // Handed over as Turtle, of which N-Triples is a subset (see syntax_for).
    RasqalDataGraph graph(rasqal_new_data_graph_from_iostream(
        world.get(), data.get(), data_base.get(), nullptr, RASQAL_DATA_GRAPH_BACKGROUND, nullptr,
        "turtle", nullptr));
    if (!graph || rasqal_query_add_data_graph(q.get(), graph.get()) != 0)
        throw InvalidInput("run_sparql: Rasqal could not take the data (out of memory?)");
    graph.release();  // owned by the query from here on

    mark = log.entries.size();
    RasqalResults results(rasqal_query_execute(q.get()));
    auto execution_error = [&](const char* what) {
        const LogEntry* error = log.first_error(mark);
        std::string message = std::string("Rasqal could not ") + what + " the query: " +
                              (error ? error->text : std::string("no reason given"));
        if (mentions_minus(query))
            message += " (MINUS fails in Rasqal 0.9.33: use OPTIONAL { ... } FILTER(!BOUND(?x)))";
        return InvalidInput(message);
    };
    if (!results) throw execution_error("run");

    QueryResult result;
    if (rasqal_query_results_is_boolean(results.get())) {
        const int value = rasqal_query_results_get_boolean(results.get());
        if (value < 0) throw execution_error("answer");
        result.is_boolean = true;
        result.boolean_value = value > 0;
        return result;
    }
    if (!rasqal_query_results_is_bindings(results.get()))
        throw InvalidInput("only SELECT and ASK queries can be run");

    // The projection of the query, not of the results: Rasqal's results know their
    // variables only once a row has been read, so an empty result would have none.
    if (raptor_sequence* projection = rasqal_query_get_bound_variable_sequence(q.get())) {
        const int size = raptor_sequence_size(projection);
        for (int i = 0; i < size; ++i) {
            const auto* v =
                static_cast<const rasqal_variable*>(raptor_sequence_get_at(projection, i));
            if (v && v->name) result.variables.emplace_back(reinterpret_cast<const char*>(v->name));
        }
    }
    const int num_variables = static_cast<int>(result.variables.size());
    while (!rasqal_query_results_finished(results.get())) {
        std::vector<std::string> row;
        std::vector<std::string> terms;
        row.reserve(static_cast<std::size_t>(num_variables));
        terms.reserve(static_cast<std::size_t>(num_variables));
        for (int i = 0; i < num_variables; ++i) {
            auto [cell, term] = convert_value(rasqal_query_results_get_binding_value_by_name(
                results.get(), reinterpret_cast<const unsigned char*>(
                                   result.variables[static_cast<std::size_t>(i)].c_str())));
            row.push_back(std::move(cell));
            terms.push_back(std::move(term));
        }
        result.rows.push_back(std::move(row));
        result.terms.push_back(std::move(terms));
        if (rasqal_query_results_next(results.get()) != 0) break;
    }
    if (log.first_error(mark)) throw execution_error("finish");
    return result;
}

// ---------------------------------------------------------------------------------------
// Writers

namespace {

/// Decodes one UTF-8 sequence at `i` (advancing it); invalid bytes give U+FFFD, one byte.
std::uint32_t next_code_point(std::string_view s, std::size_t& i) {
    const auto b0 = static_cast<unsigned char>(s[i]);
    std::size_t len = 0;
    std::uint32_t cp = 0;
    if (b0 < 0x80) {
        ++i;
        return b0;
    }
    if ((b0 & 0xE0) == 0xC0) {
        len = 2;
        cp = b0 & 0x1F;
    } else if ((b0 & 0xF0) == 0xE0) {
        len = 3;
        cp = b0 & 0x0F;
    } else if ((b0 & 0xF8) == 0xF0) {
        len = 4;
        cp = b0 & 0x07;
    } else {
        ++i;
        return 0xFFFD;
    }
    if (i + len > s.size()) {
        ++i;
        return 0xFFFD;
    }
    for (std::size_t k = 1; k < len; ++k) {
        const auto b = static_cast<unsigned char>(s[i + k]);
        if ((b & 0xC0) != 0x80) {
            ++i;
            return 0xFFFD;
        }
        cp = (cp << 6) | (b & 0x3F);
    }
    static const std::uint32_t min_for_len[] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < min_for_len[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
        ++i;
        return 0xFFFD;
    }
    i += len;
    return cp;
}

/// Columns a code point takes in a terminal: 0 for combining marks and zero-width
/// characters, 2 for East Asian wide and fullwidth characters and emoji, else 1.
int code_point_width(std::uint32_t cp) {
    struct Range {
        std::uint32_t first, last;
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
            append_hex_escape(out, c);
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

void write_csv_field(std::ostream& out, const std::string& field) {
    if (field.find_first_of(",\"\r\n") == std::string::npos) {
        out << field;
        return;
    }
    out << '"';
    for (char ch : field) {
        if (ch == '"') out << '"';
        out << ch;
    }
    out << '"';
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

std::string json_string(std::string_view s) {
    std::string out = "\"";
    for (std::size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c < 0x80) {
            ++i;
            switch (c) {
                case '"':
                    out += "\\\"";
                    break;
                case '\\':
                    out += "\\\\";
                    break;
                case '\n':
                    out += "\\n";
                    break;
                case '\r':
                    out += "\\r";
                    break;
                case '\t':
                    out += "\\t";
                    break;
                case '\b':
                    out += "\\b";
                    break;
                case '\f':
                    out += "\\f";
                    break;
                default:
                    if (c < 0x20)
                        append_hex_escape(out, c);
                    else
                        out += static_cast<char>(c);
            }
        } else {
            // Valid UTF-8 passes through; an invalid byte becomes U+FFFD, so the output is
            // always valid JSON.
            append_utf8(out, next_code_point(s, i));
        }
    }
    out += '"';
    return out;
}

/// SPARQL 1.1 Query Results JSON Format (W3C Recommendation, 2013).
void write_json(std::ostream& out, const QueryResult& result) {
    if (result.is_boolean) {
        out << "{\n  \"head\": {},\n  \"boolean\": " << (result.boolean_value ? "true" : "false")
            << "\n}\n";
        return;
    }
    out << "{\n  \"head\": {\"vars\": [";
    for (std::size_t c = 0; c < result.variables.size(); ++c)
        out << (c > 0 ? ", " : "") << json_string(result.variables[c]);
    out << "]},\n  \"results\": {\"bindings\": [";
    for (std::size_t r = 0; r < result.rows.size(); ++r) {
        out << (r > 0 ? ",\n" : "\n") << "    {";
        bool first = true;
        for (std::size_t c = 0; c < result.variables.size(); ++c) {
            const Term term = cell_term(result, r, c);
            if (term.kind == Term::Kind::Unbound) continue;
            out << (first ? "" : ", ") << json_string(result.variables[c]) << ": {\"type\": ";
            first = false;
            switch (term.kind) {
                case Term::Kind::Iri:
                    out << "\"uri\"";
                    break;
                case Term::Kind::Blank:
                    out << "\"bnode\"";
                    break;
                default:
                    out << "\"literal\"";
            }
            out << ", \"value\": " << json_string(term.value);
            if (!term.language.empty()) out << ", \"xml:lang\": " << json_string(term.language);
            if (!term.datatype.empty()) out << ", \"datatype\": " << json_string(term.datatype);
            out << '}';
        }
        out << '}';
    }
    out << (result.rows.empty() ? "" : "\n  ") << "]}\n}\n";
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
