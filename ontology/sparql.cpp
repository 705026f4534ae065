// SPARQL over geotex output, embedded: Raptor2 reads the data files into geotex's indexed
// store (ontology/detail/triple_store.*), Rasqal 0.9.33 runs the query over it
// (ontology/detail/rasqal_source.*), geotex rewrites what Rasqal lacks or gets wrong before
// (ontology/detail/sparql_text.*) and applies the solution modifiers after
// (ontology/detail/solution_modifiers.*), and the results are written as a text table, CSV
// or SPARQL 1.1 results JSON.

#include "ontology/sparql.hpp"

#include <rasqal.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geometry/detail/c_handle.hpp"
#include "geometry/detail/text.hpp"
#include "geometry/errors.hpp"
#include "ontology/detail/query_deadline.hpp"
#include "ontology/detail/raptor_handles.hpp"
#include "ontology/detail/rasqal_source.hpp"
#include "ontology/detail/solution_modifiers.hpp"
#include "ontology/detail/sparql_join_order.hpp"
#include "ontology/detail/sparql_text.hpp"
#include "ontology/detail/triple_store.hpp"
#include "ontology/rdf_lexical.hpp"

namespace geotex {

namespace {

// ---------------------------------------------------------------------------------------
// Owning handles for the C objects of Raptor (ontology/detail/raptor_handles.hpp) and Rasqal.

template <auto Free>
using Deleter = detail::CDeleter<Free>;
using detail::RaptorParser;
using detail::RaptorUri;
using detail::RaptorWorld;

using RasqalWorld = std::unique_ptr<rasqal_world, Deleter<rasqal_free_world>>;
using RasqalQuery = std::unique_ptr<rasqal_query, Deleter<rasqal_free_query>>;
using RasqalResults = std::unique_ptr<rasqal_query_results, Deleter<rasqal_free_query_results>>;

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
// read back by the result writers in query_result_writer.cpp).

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
                    detail::append_u_escape(out, c);
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
            detail::append_u_escape(out, c);
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

[[noreturn]] void throw_out_of_time(const detail::Deadline& deadline) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", deadline.seconds());
    throw QueryTimeout(std::string("the query ran out of time: its limit of ") + seconds +
                       " s passed before it finished; no result is written");
}

// ---------------------------------------------------------------------------------------
// U+0000 in literals. Raptor 2.0.15's Turtle and N-Quads parsers decode the escape \u0000
// and then measure the string with strlen(): the value is cut at it. The escapes are replaced
// before parsing by a noncharacter that no RDF data uses, turned back into U+0000 when the
// literal is taken (GraphBuilder).

/// U+FDD0 in UTF-8.
constexpr std::string_view kNulStandIn = "\xEF\xB7\x90";

/// Replaces in `bytes` the escapes \u0000 and \U00000000 (not those of an escaped backslash,
/// \\u0000) with kNulStandIn; whether there was one. Throws InvalidInput when the file holds
/// U+FDD0 itself, as text or as an escape, besides such an escape: it could not be told apart.
bool protect_nul_escapes(std::string& bytes, const std::string& path) {
    static const std::string_view forms[] = {"\\u0000", "\\U00000000"};
    bool found = false;
    std::string out;
    std::size_t copied = 0;
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        if (bytes[i] != '\\') continue;
        const std::string_view rest = std::string_view(bytes).substr(i);
        const std::string_view* form = nullptr;
        for (const std::string_view& f : forms)
            if (rest.compare(0, f.size(), f) == 0) form = &f;
        if (!form) {
            ++i;  // an escape of two characters or more: its second is no backslash of ours
            continue;
        }
        out.append(bytes, copied, i - copied);
        out += kNulStandIn;
        copied = i + form->size();
        i = copied - 1;
        found = true;
    }
    if (!found) return false;
    out.append(bytes, copied, std::string::npos);
    auto holds = [&](std::string_view what) { return out.find(what) != std::string::npos; };
    if (bytes.find(kNulStandIn) != std::string::npos || holds("\\uFDD0") || holds("\\ufdd0") ||
        holds("\\U0000FDD0") || holds("\\U0000fdd0"))
        throw InvalidInput(
            "a literal holds U+0000 (\\u0000) and the file holds U+FDD0: geotex cannot keep "
            "both apart with Raptor 2.0.15 (which cuts a value at U+0000)",
            path);
    bytes = std::move(out);
    return true;
}

// ---------------------------------------------------------------------------------------
// Data: every file is parsed with Raptor into one TripleStore, a set: a triple written twice
// (in one file, or in two files, as the dictionary concepts of two annotation files are)
// matches once, as the SPARQL dataset is a set.

struct GraphBuilder {
    detail::TripleStore& store;
    std::unordered_map<std::string, std::string> blank_labels;  // of the current file
    std::size_t file_index = 0;
    std::size_t num_blanks = 0;
    std::string key;             // scratch
    std::exception_ptr failure;  // thrown inside the statement handler
    raptor_parser* parser = nullptr;
    const detail::Deadline& limit;
    detail::DeadlineCheck deadline{&limit};
    bool restore_nul = false;  // the file's \u0000 escapes became kNulStandIn (protect_nul_escapes)
    std::string lexical;       // scratch

    GraphBuilder(detail::TripleStore& s, std::size_t file, const detail::Deadline& d)
        : store(s), file_index(file), limit(d) {}

    detail::TripleStore::TermId term_id(const raptor_term* term) {
        key.clear();
        switch (term->type) {
            case RAPTOR_TERM_TYPE_URI: {
                std::size_t len = 0;
                const unsigned char* s = raptor_uri_as_counted_string(term->value.uri, &len);
                detail::append_iri_key(key,
                                       std::string_view(reinterpret_cast<const char*>(s), len));
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
                detail::append_blank_key(key, found->second);
                break;
            }
            case RAPTOR_TERM_TYPE_LITERAL: {
                const raptor_term_literal_value& lit = term->value.literal;
                std::string_view datatype;
                if (lit.datatype) {
                    std::size_t len = 0;
                    const unsigned char* s = raptor_uri_as_counted_string(lit.datatype, &len);
                    datatype = std::string_view(reinterpret_cast<const char*>(s), len);
                }
                std::string_view text(reinterpret_cast<const char*>(lit.string), lit.string_len);
                if (restore_nul && text.find(kNulStandIn) != std::string_view::npos) {
                    lexical.assign(text);
                    for (std::size_t at = lexical.find(kNulStandIn); at != std::string::npos;
                         at = lexical.find(kNulStandIn, at + 1))
                        lexical.replace(at, kNulStandIn.size(), 1, '\0');
                    text = lexical;
                }
                detail::append_literal_key(
                    key, text,
                    lit.language ? std::string_view(reinterpret_cast<const char*>(lit.language),
                                                    lit.language_len)
                                 : std::string_view(),
                    datatype);
                break;
            }
            default:
                detail::append_blank_key(key, "unknown");
        }
        return store.intern(key);
    }

    void add(const raptor_statement* st) {
        if (deadline.passed()) throw_out_of_time(limit);
        const auto s = term_id(st->subject);
        const auto p = term_id(st->predicate);
        const auto o = term_id(st->object);
        store.add(s, p, o);
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

/// The Raptor parser for a data file, or "" when its extension is unknown (syntax_for then
/// says so, in file order).
const char* syntax_for_or_null(const std::string& path) {
    try {
        return syntax_for(path).parser;
    } catch (const InvalidInput&) {
        return "";
    }
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

/// The triples of one data file, read with `raptor`, a world that no other thread uses
/// meanwhile (files are read on several threads).
detail::TripleStore load_data_file(raptor_world* raptor_world, const std::string& path,
                                   std::size_t file_index, const detail::Deadline& deadline) {
    std::string bytes = read_data_file(path);
    const Syntax syntax = syntax_for(path);
    const bool nul_escapes = std::strcmp(syntax.parser, "rdfxml") != 0 && protect_nul_escapes(bytes, path);

    MessageLog log;
    raptor_world_set_log_handler(raptor_world, &log, on_log_message);

    // Relative IRIs in the file resolve against the file's own URI, as with roqet -D.
    std::error_code ec;
    const std::string absolute = std::filesystem::absolute(path, ec).string();
    unsigned char* uri_string =
        raptor_uri_filename_to_uri_string(ec ? path.c_str() : absolute.c_str());
    if (!uri_string) throw IoError("cannot make a file URI for the RDF data file", path);
    RaptorUri base(raptor_new_uri(raptor_world, uri_string));
    raptor_free_memory(uri_string);

    RaptorParser parser(raptor_new_parser(raptor_world, syntax.parser));
    if (!base || !parser) throw IoError("Raptor could not start a parser (out of memory?)", path);
    raptor_parser_set_option(parser.get(), RAPTOR_OPTION_NO_NET, nullptr, 1);

    detail::TripleStore part;
    GraphBuilder builder(part, file_index, deadline);
    builder.restore_nul = nul_escapes;
    builder.parser = parser.get();
    raptor_parser_set_statement_handler(parser.get(), &builder, on_statement);

    int rc = raptor_parser_parse_start(parser.get(), base.get());
    if (rc == 0)
        rc = raptor_parser_parse_chunk(
            parser.get(), reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), 1);
    builder.parser = nullptr;
    if (builder.failure) std::rethrow_exception(builder.failure);
    if (const LogEntry* error = log.first_error(0))
        throw ParseError(std::string("invalid ") + syntax.name + ": " + error->text, path,
                         error->line, error->column);
    if (rc != 0)
        throw ParseError(std::string("invalid ") + syntax.name + " (no reason given)", path);
    return part;
}

/// The union of the data files, as a set. The files are parsed in parallel, each into a
/// store of its own, and merged in the order given, so that the terms' ids (and the order
/// of rows without ORDER BY) do not depend on the threads. A failure is that of the first
/// failing file in that order.
///
/// Each thread parses with a Raptor world of its own, opened and freed on the calling
/// thread: opening a world sets up libxml2 and libcurl, process-wide (one run in ten crashed
/// when two threads did it at once), and libxml2 keeps per-thread state that it never frees
/// on a thread it was set up from. RDF/XML, parsed with libxml2, is read on the calling
/// thread for the same reason. As many threads as TBB may use (--threads), no more than
/// files.
void load_data(const std::vector<std::string>& files, detail::TripleStore& store,
               const detail::Deadline& deadline) {
    const std::size_t n = files.size();
    std::vector<detail::TripleStore> parts(n);
    std::vector<std::exception_ptr> failures(n);
    auto load = [&](raptor_world* world, std::size_t i) {
        try {
            parts[i] = load_data_file(world, files[i], i, deadline);
        } catch (...) {
            failures[i] = std::current_exception();
        }
    };
    auto on_calling_thread = [&](std::size_t i) {
        return std::strcmp(syntax_for_or_null(files[i]), "rdfxml") == 0;
    };

    const std::size_t num_threads = std::max<std::size_t>(
        1, std::min<std::size_t>(
               n, static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()))));
    std::vector<RaptorWorld> worlds;
    for (std::size_t t = 0; t < num_threads; ++t) {
        worlds.emplace_back(raptor_new_world());
        if (!worlds.back() || raptor_world_open(worlds.back().get()) != 0)
            throw IoError("Raptor could not start (out of memory?)", n > 0 ? files[0] : "");
    }
    std::atomic<std::size_t> next{0};
    auto work = [&](raptor_world* world) {
        for (std::size_t i = next++; i < n; i = next++)
            if (!on_calling_thread(i)) load(world, i);
    };
    std::vector<std::thread> threads;
    try {
        for (std::size_t t = 1; t < num_threads; ++t) threads.emplace_back(work, worlds[t].get());
    } catch (...) {
        // No thread to be had: the calling thread reads what the others would have.
    }
    work(worlds[0].get());
    for (std::thread& t : threads) t.join();
    for (std::size_t i = 0; i < n; ++i)
        if (on_calling_thread(i)) load(worlds[0].get(), i);

    for (const std::exception_ptr& failure : failures)
        if (failure) std::rethrow_exception(failure);
    std::size_t total = 0;
    for (const detail::TripleStore& part : parts) total += part.num_triples();
    store.reserve(total);
    for (detail::TripleStore& part : parts) {
        store.merge(part);
        part = detail::TripleStore();
    }
    store.finish();
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

/// Throws InvalidInput at the first SERVICE keyword (strings, comments, IRIs and prefixed
/// names are not keywords): Rasqal would fetch its IRI, over the network or from a local
/// file, and a query must read nothing but its data files.
void refuse_service(const std::string& query) {
    for (const detail::SparqlToken& t : detail::tokenize_sparql(query)) {
        if (t.kind != detail::SparqlToken::Kind::Word || t.end - t.begin != 7) continue;
        std::string word = query.substr(t.begin, 7);
        for (char& c : word) c = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c;
        if (word == "SERVICE")
            throw InvalidInput(
                "SERVICE is refused: geotex query reads only the data files it is given, "
                "never a URI (query the other endpoint apart and give its results as a file)",
                "", t.line, t.column);
    }
}

/// The expected number of triples that a pattern matches (detail::PatternCost) in `store`.
double pattern_cost(const detail::TripleStore& store, const std::string& predicate,
                    bool subject_fixed, bool object_fixed) {
    auto per = [](std::size_t n, std::size_t d) {
        return d == 0 ? 0.0 : static_cast<double>(n) / static_cast<double>(d);
    };
    std::size_t n = store.num_triples(), subjects = store.num_subjects(),
                objects = store.num_objects();
    if (!predicate.empty()) {
        std::string key;
        detail::append_iri_key(key, predicate);
        const detail::TripleStore::TermId id = store.find(key);
        if (id == detail::TripleStore::kAny) return 0;  // no such predicate: nothing matches
        const detail::TripleStore::PredicateStats st = store.predicate_stats(id);
        n = st.num_triples;
        subjects = st.num_subjects;
        objects = st.num_objects;
    }
    if (subject_fixed && object_fixed) return std::min(1.0, per(n, std::max(subjects, objects)));
    if (subject_fixed) return per(n, subjects);
    if (object_fixed) return per(n, objects);
    return static_cast<double>(n);
}

/// Whether a graph pattern or one of its sub-patterns is a SERVICE (a second guard behind
/// refuse_service, on what Rasqal parsed).
bool has_service(rasqal_graph_pattern* gp) {
    if (!gp) return false;
    if (rasqal_graph_pattern_get_operator(gp) == RASQAL_GRAPH_PATTERN_OPERATOR_SERVICE)
        return true;
    for (int i = 0;; ++i) {
        rasqal_graph_pattern* sub = rasqal_graph_pattern_get_sub_graph_pattern(gp, i);
        if (!sub) return false;
        if (has_service(sub)) return true;
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

namespace {

/// Rasqal's query, prepared from `text`; throws ParseError with Rasqal's message.
RasqalQuery prepare_query(rasqal_world* world, MessageLog& log, const std::string& text) {
    RasqalQuery q(rasqal_new_query(world, "sparql11-query", nullptr));
    if (!q) throw InvalidInput("run_sparql: Rasqal has no SPARQL 1.1 query language");
    const std::size_t mark = log.entries.size();
    if (rasqal_query_prepare(q.get(), reinterpret_cast<const unsigned char*>(text.c_str()),
                             nullptr) != 0) {
        const LogEntry* error = log.first_error(mark);
        throw ParseError("SPARQL: " + (error ? error->text : std::string("syntax error")), "",
                         error ? error->line : 0, error ? error->column : 0);
    }
    return q;
}

/// The names of the GROUP BY keys that are plain variables.
std::vector<std::string> group_variables(rasqal_query* q) {
    std::vector<std::string> names;
    raptor_sequence* conditions = rasqal_query_get_group_conditions_sequence(q);
    const int size = conditions ? raptor_sequence_size(conditions) : 0;
    for (int i = 0; i < size; ++i) {
        const auto* e = static_cast<const rasqal_expression*>(raptor_sequence_get_at(conditions, i));
        if (e && e->op == RASQAL_EXPR_LITERAL && e->literal)
            if (const rasqal_variable* v = rasqal_literal_as_variable(e->literal))
                if (v->name) names.emplace_back(reinterpret_cast<const char*>(v->name));
    }
    return names;
}

}  // namespace

QueryResult run_sparql(const std::string& query_text, const std::vector<std::string>& data_files,
                       const QueryParams& params) {
    if (!(params.timeout >= 0) || !std::isfinite(params.timeout))
        throw InvalidInput("run_sparql: the timeout must be a finite number of seconds >= 0");
    const detail::Deadline deadline =
        params.timeout > 0 ? detail::Deadline(params.timeout) : detail::Deadline();
    // A byte order mark is no part of the query (editors on Windows write one); the columns
    // of line 1 are then counted after it, as an editor shows them.
    const std::string query = query_text.compare(0, 3, "\xEF\xBB\xBF") == 0
                                  ? query_text.substr(3)
                                  : query_text;
    refuse_service(query);
    check_values_form(query);
    // Rasqal has no property paths: those that are a fixed set of triple patterns become
    // them, with new variables, which no result shows.
    std::string fresh_prefix;
    std::vector<detail::ConcatColumn> concat_columns;
    std::string text = detail::rewrite_aggregates(
        detail::rewrite_property_paths(query, &fresh_prefix), &concat_columns);

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

    RasqalQuery q = prepare_query(world.get(), log, text);
    const rasqal_query_verb verb = rasqal_query_get_verb(q.get());
    if (verb != RASQAL_QUERY_VERB_SELECT && verb != RASQAL_QUERY_VERB_ASK) {
        const char* name = verb == RASQAL_QUERY_VERB_CONSTRUCT  ? "CONSTRUCT"
                           : verb == RASQAL_QUERY_VERB_DESCRIBE ? "DESCRIBE"
                                                                : "this kind of";
        throw InvalidInput(std::string("only SELECT and ASK queries can be run, not ") + name +
                           " queries");
    }
    if (has_service(rasqal_query_get_query_graph_pattern(q.get())))
        throw InvalidInput(
            "SERVICE is refused: geotex query reads only the data files it is given, never a URI");
    if (rasqal_query_get_data_graph(q.get(), 0) != nullptr)
        throw InvalidInput(
            "FROM and FROM NAMED are not supported: give the data files to query "
            "instead (their union is the default graph)");

    QueryResult result;
    // The projection of the query, not of the results: Rasqal's results know their
    // variables only once a row has been read, so an empty result would have none.
    std::vector<std::string> all_variables;
    if (raptor_sequence* projection = rasqal_query_get_bound_variable_sequence(q.get())) {
        const int size = raptor_sequence_size(projection);
        for (int i = 0; i < size; ++i) {
            const auto* v =
                static_cast<const rasqal_variable*>(raptor_sequence_get_at(projection, i));
            if (v && v->name) all_variables.emplace_back(reinterpret_cast<const char*>(v->name));
        }
    }
    for (const std::string& name : all_variables)
        if (name.compare(0, fresh_prefix.size(), fresh_prefix) != 0)
            result.variables.push_back(name);
    detail::SolutionModifiers modifiers = detail::plan_solution_modifiers(q.get(), result.variables);

    detail::TripleStore store;
    load_data(data_files, store, deadline);

    // The join order, from the data's statistics (the query was prepared once before, so that
    // its errors come before reading the data).
    const std::string ordered = detail::order_triple_patterns(
        text, [&](const std::string& predicate, bool subject_fixed, bool object_fixed) {
            return pattern_cost(store, predicate, subject_fixed, object_fixed);
        });
    if (ordered != text) {
        text = ordered;
        q = prepare_query(world.get(), log, text);
    }

    // Declared after the worlds, so destroyed before them; before the results, so destroyed
    // after them (both hold references to its literals).
    detail::RasqalTripleSource source(world.get(), store);
    if (!source.attach()) throw InvalidInput("run_sparql: Rasqal refused the triple store");
    source.set_deadline(&deadline);
    detail::DeadlineCheck rows_deadline(&deadline);
    // After each run: rows cut short by the deadline are no answer.
    auto check_time = [&] {
        if (source.timed_out() || rows_deadline.seen()) throw_out_of_time(deadline);
    };

    std::size_t mark = 0;
    auto execution_error = [&](const char* what) {
        check_time();  // a pattern cut short may make Rasqal fail: the time is the reason
        const LogEntry* error = log.first_error(mark);
        std::string message = std::string("Rasqal could not ") + what + " the query: " +
                              (error ? error->text : std::string("no reason given"));
        if (mentions_minus(query))
            message += " (MINUS fails in Rasqal 0.9.33: use OPTIONAL { ... } FILTER(!BOUND(?x)))";
        return InvalidInput(message);
    };
    // Runs `rq` (prepared from `rq_text`) without the modifiers that geotex applies itself.
    auto select_rows = [&](RasqalQuery& rq, const std::string& rq_text,
                           const detail::SolutionModifiers& m, detail::ResultRows& rows) {
        if (!m.order.empty()) rq = prepare_query(world.get(), log, detail::remove_order_by(rq_text));
        detail::remove_solution_modifiers(rq.get(), m);
        source.allow_correlation(rq.get());
        mark = log.entries.size();
        RasqalResults results(rasqal_query_execute(rq.get()));
        if (!results) throw execution_error("run");
        if (!rasqal_query_results_is_bindings(results.get()))
            throw InvalidInput("only SELECT and ASK queries can be run");
        const std::size_t num_variables = result.variables.size();
        while (!rasqal_query_results_finished(results.get())) {
            if (rows_deadline.passed_now()) break;
            std::vector<std::string> cells;
            std::vector<std::string> terms;
            cells.reserve(num_variables);
            terms.reserve(num_variables);
            std::vector<rasqal_literal*> values(num_variables, nullptr);
            for (std::size_t i = 0; i < num_variables; ++i) {
                values[i] = rasqal_query_results_get_binding_value_by_name(
                    results.get(),
                    reinterpret_cast<const unsigned char*>(result.variables[i].c_str()));
                auto [cell, term] = convert_value(values[i]);
                cells.push_back(std::move(cell));
                terms.push_back(std::move(term));
            }
            std::vector<rasqal_literal*> keys;
            for (const auto& key : m.order) {
                rasqal_literal* l = values[key.first];
                keys.push_back(l ? rasqal_new_literal_from_literal(l) : nullptr);
            }
            rows.cells.push_back(std::move(cells));
            rows.terms.push_back(std::move(terms));
            rows.keys.push_back(std::move(keys));
            if (rasqal_query_results_next(results.get()) != 0) break;
        }
        check_time();
        if (log.first_error(mark)) throw execution_error("finish");
    };

    if (verb == RASQAL_QUERY_VERB_ASK) {
        source.allow_correlation(q.get());
        mark = log.entries.size();
        RasqalResults results(rasqal_query_execute(q.get()));
        if (!results) throw execution_error("run");
        const int value = rasqal_query_results_get_boolean(results.get());
        check_time();
        if (value < 0) throw execution_error("answer");
        result.is_boolean = true;
        result.boolean_value = value > 0;
        return result;
    }

    const std::vector<std::string> group_keys = group_variables(q.get());
    auto rows = std::make_unique<detail::ResultRows>();
    select_rows(q, text, modifiers, *rows);

    // Rasqal 0.9.33 answers a GROUP BY over no solution with one group whose keys are unbound
    // (SPARQL: no group, no row). Such a row is kept only if the WHERE clause has a solution.
    if (!group_keys.empty() && rows->cells.size() == 1) {
        bool keys_unbound = true;
        for (std::size_t i = 0; i < result.variables.size(); ++i)
            if (std::find(group_keys.begin(), group_keys.end(), result.variables[i]) !=
                    group_keys.end() &&
                !rows->terms[0][i].empty())
                keys_unbound = false;
        const std::string ask = keys_unbound ? detail::where_clause_as_ask(text) : std::string();
        if (!ask.empty()) {
            RasqalQuery check = prepare_query(world.get(), log, ask);
            source.allow_correlation(check.get());
            mark = log.entries.size();
            RasqalResults answer(rasqal_query_execute(check.get()));
            if (!answer) throw execution_error("run");
            const int value = rasqal_query_results_get_boolean(answer.get());
            check_time();
            if (value < 0) throw execution_error("answer");
            if (value == 0) rows = std::make_unique<detail::ResultRows>();
        }
    }

    if (!detail::apply_solution_modifiers(modifiers, *rows)) {
        // An ORDER BY column of values of several kinds: Rasqal's own ORDER BY orders them.
        modifiers.order.clear();
        rows = std::make_unique<detail::ResultRows>();
        RasqalQuery again = prepare_query(world.get(), log, text);
        select_rows(again, text, modifiers, *rows);
        detail::apply_solution_modifiers(modifiers, *rows);
    }
    result.rows = std::move(rows->cells);
    result.terms = std::move(rows->terms);
    // The GROUP_CONCAT columns whose separator Rasqal would have ignored (rewrite_aggregates).
    for (const detail::ConcatColumn& c : concat_columns) {
        const auto at = std::find(result.variables.begin(), result.variables.end(), c.variable);
        if (at == result.variables.end()) continue;
        const auto column = static_cast<std::size_t>(at - result.variables.begin());
        for (std::size_t i = 0; i < result.rows.size(); ++i) {
            // Unbound: an error in the group (SPARQL's GROUP_CONCAT passes errors on).
            if (result.terms[i][column].empty()) continue;
            std::string& cell = result.rows[i][column];
            cell = detail::join_concat_parts(cell, c.separator);
            result.terms[i][column] = nt_literal(cell, "", "");
        }
    }
    return result;
}

}  // namespace geotex

// Rasqal 0.9.33 writes a double that it computes (AVG, SUM, arithmetic) with 15 significant
// digits and then cuts the mantissa at the last zero that follows another digit, even when
// non-zero digits come after it: the mean 0.080676369739619 comes out as "8.0E-2", and that
// text is the value it hands out. Its calls to this formatter go through the dynamic symbol
// table, so this definition, linked into the program that embeds Rasqal, replaces it: the
// shortest form that reads back to the same double, as the RDF writer writes doubles. Rasqal
// frees the text with free(); no exception may cross into its C code.
// (tests/test_sparql.cpp, "computed doubles", fails if the replacement stops taking effect.)
extern "C" unsigned char* rasqal_xsd_format_double(double d, size_t* len_p) {
    try {
        const std::string text = std::isfinite(d)
                                     ? geotex::rdf_detail::double_lexical(d, "a double")
                                 : std::isnan(d) ? "NaN"
                                 : d > 0         ? "INF"
                                                 : "-INF";
        auto* out = static_cast<unsigned char*>(std::malloc(text.size() + 1));
        if (!out) return nullptr;
        std::memcpy(out, text.c_str(), text.size() + 1);
        if (len_p) *len_p = text.size();
        return out;
    } catch (...) {
        return nullptr;
    }
}
