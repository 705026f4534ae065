// Reading the data files of a query (ontology/detail/sparql_data.hpp).

#include "ontology/detail/sparql_data.hpp"

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "ontology/detail/message_log.hpp"
#include "ontology/detail/raptor_handles.hpp"

namespace geotex::detail {

namespace {

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
    TripleStore& store;
    std::unordered_map<std::string, std::string> blank_labels;  // of the current file
    std::size_t file_index = 0;
    std::size_t num_blanks = 0;
    std::string key;             // scratch
    std::exception_ptr failure;  // thrown inside the statement handler
    raptor_parser* parser = nullptr;
    const Deadline& limit;
    DeadlineCheck deadline{&limit};
    bool restore_nul = false;  // the file's \u0000 escapes became kNulStandIn (protect_nul_escapes)
    std::string lexical;       // scratch

    GraphBuilder(TripleStore& s, std::size_t file, const Deadline& d)
        : store(s), file_index(file), limit(d) {}

    TripleStore::TermId term_id(const raptor_term* term) {
        key.clear();
        switch (term->type) {
            case RAPTOR_TERM_TYPE_URI: {
                std::size_t len = 0;
                const unsigned char* s = raptor_uri_as_counted_string(term->value.uri, &len);
                append_iri_key(key, std::string_view(reinterpret_cast<const char*>(s), len));
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
                append_blank_key(key, found->second);
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
                append_literal_key(
                    key, text,
                    lit.language ? std::string_view(reinterpret_cast<const char*>(lit.language),
                                                    lit.language_len)
                                 : std::string_view(),
                    datatype);
                break;
            }
            default:
                append_blank_key(key, "unknown");
        }
        return store.intern(key);
    }

    void add(const raptor_statement* st) {
        if (deadline.passed()) limit.throw_timeout();
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
TripleStore load_data_file(raptor_world* raptor_world, const std::string& path,
                           std::size_t file_index, const Deadline& deadline) {
    std::string bytes = read_data_file(path);
    const Syntax syntax = syntax_for(path);
    const bool nul_escapes =
        std::strcmp(syntax.parser, "rdfxml") != 0 && protect_nul_escapes(bytes, path);

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

    TripleStore part;
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

}  // namespace

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
void load_data(const std::vector<std::string>& files, TripleStore& store,
               const Deadline& deadline) {
    const std::size_t n = files.size();
    std::vector<TripleStore> parts(n);
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

    // The arena's concurrency ignores a tbb::global_control (geotex -j N): both limit.
    const int allowed = static_cast<int>(std::min<std::size_t>(
        tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism),
        static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()))));
    const std::size_t num_threads = std::max<std::size_t>(
        1, std::min<std::size_t>(n, static_cast<std::size_t>(std::max(1, allowed))));
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
    for (const TripleStore& part : parts) total += part.num_triples();
    store.reserve(total);
    for (TripleStore& part : parts) {
        store.merge(part);
        part = TripleStore();
    }
    store.finish();
}

}  // namespace geotex::detail
