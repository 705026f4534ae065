// Turtle re-written as N-Triples chunks and N-Quads, with Raptor2's parser and writers.

#include "ontology/rdf_transcode.hpp"

#include <raptor2.h>

#include <exception>
#include <filesystem>
#include <ostream>
#include <string>
#include <type_traits>
#include <utility>

#include "common/errors.hpp"
#include "ontology/detail/raptor_handles.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex {

namespace detail {

/// The first error Raptor logs, kept for the exception (the library prints nothing). Not in
/// the anonymous namespace: NQuadsWriter::Impl, a class of the library, holds one.
struct RaptorFirstError {
    bool set = false;
    std::string text;
    long line = 0;
    long column = 0;
};

}  // namespace detail

namespace {

using detail::RaptorIostream;
using detail::RaptorParser;
using detail::RaptorSerializer;
using detail::RaptorTerm;
using detail::RaptorUri;
using detail::RaptorWorld;

using FirstError = detail::RaptorFirstError;

void on_log(void* user_data, raptor_log_message* message) noexcept {
    auto* first = static_cast<FirstError*>(user_data);
    if (message->level < RAPTOR_LOG_LEVEL_ERROR || first->set) return;
    first->set = true;
    try {
        first->text = message->text ? message->text : "";
        while (!first->text.empty() && (first->text.back() == '\n' || first->text.back() == ' '))
            first->text.pop_back();
    } catch (...) {
        // No memory for the text: the error is still reported, without it.
    }
    if (message->locator) {
        first->line = message->locator->line > 0 ? message->locator->line : 0;
        first->column = message->locator->column > 0 ? message->locator->column : 0;
    }
}

RaptorWorld open_world(FirstError& errors) {
    RaptorWorld world(raptor_new_world());
    if (!world || raptor_world_open(world.get()) != 0)
        throw IoError("cannot start Raptor2 (out of memory?)");
    raptor_world_set_log_handler(world.get(), &errors, &on_log);
    return world;
}

/// An iostream that appends to a std::string.
class StringStream {
  public:
    StringStream(raptor_world* world, std::string* target) : target_(target) {
        handler_.version = 2;  // Raptor 2.0.15 refuses a version 1 handler
        handler_.write_byte = &StringStream::write_byte;
        handler_.write_bytes = &StringStream::write_bytes;
        stream_.reset(raptor_new_iostream_from_handler(world, this, &handler_));
        if (!stream_) throw IoError("Raptor2 cannot create an output stream (out of memory?)");
    }
    StringStream(const StringStream&) = delete;
    StringStream& operator=(const StringStream&) = delete;

    raptor_iostream* get() const { return stream_.get(); }
    void retarget(std::string* target) { target_ = target; }
    bool failed() const { return failed_; }

  private:
    static int write_byte(void* context, const int byte) {
        auto* self = static_cast<StringStream*>(context);
        try {
            self->target_->push_back(static_cast<char>(byte));
            return 0;
        } catch (...) {
            self->failed_ = true;
            return 1;
        }
    }
    static int write_bytes(void* context, const void* ptr, size_t size, size_t nmemb) {
        auto* self = static_cast<StringStream*>(context);
        try {
            self->target_->append(static_cast<const char*>(ptr), size * nmemb);
            return static_cast<int>(nmemb);
        } catch (...) {
            self->failed_ = true;
            return 0;
        }
    }

    std::string* target_;
    bool failed_ = false;
    raptor_iostream_handler handler_{};  // Raptor keeps a pointer to it
    RaptorIostream stream_;              // last, so freed first
};

/// Parses `text` as Turtle with base the file URI of `path`, calling `on_statement` for
/// every triple. Exceptions thrown by it stop the parse and are rethrown; a syntax error is
/// a ParseError naming `path`, line and column.
template <class Fn>
void parse_turtle(raptor_world* world, FirstError& errors, std::string_view text,
                  const std::string& path, Fn&& on_statement) {
    struct Context {
        std::remove_reference_t<Fn>* fn;
        raptor_parser* parser;
        std::exception_ptr failure;
    };
    std::error_code ec;
    const std::string absolute = std::filesystem::absolute(path, ec).string();
    unsigned char* uri_string =
        raptor_uri_filename_to_uri_string(ec || path.empty() ? "/" : absolute.c_str());
    if (!uri_string) throw IoError("cannot make a file URI", path);
    RaptorUri base(raptor_new_uri(world, uri_string));
    raptor_free_memory(uri_string);
    RaptorParser parser(raptor_new_parser(world, "turtle"));
    if (!base || !parser) throw IoError("Raptor2 could not start a parser (out of memory?)", path);
    raptor_parser_set_option(parser.get(), RAPTOR_OPTION_NO_NET, nullptr, 1);
    Context context{&on_statement, parser.get(), nullptr};
    raptor_parser_set_statement_handler(parser.get(), &context,
                                        [](void* user_data, raptor_statement* statement) {
                                            auto* c = static_cast<Context*>(user_data);
                                            if (c->failure) return;
                                            try {
                                                (*c->fn)(statement);
                                            } catch (...) {
                                                c->failure = std::current_exception();
                                                raptor_parser_parse_abort(c->parser);
                                            }
                                        });
    errors = FirstError{};
    int rc = raptor_parser_parse_start(parser.get(), base.get());
    if (rc == 0)
        rc = raptor_parser_parse_chunk(
            parser.get(), reinterpret_cast<const unsigned char*>(text.data()), text.size(), 1);
    if (context.failure) std::rethrow_exception(context.failure);
    if (errors.set)
        throw ParseError("invalid Turtle: " + errors.text, path, errors.line, errors.column);
    if (rc != 0) throw ParseError("invalid Turtle (no reason given)", path);
}

}  // namespace

NTriplesChunks make_ntriples_chunks(std::string_view text, const std::string& path,
                                    const NTriplesChunkParams& params) {
    if (params.max_triples == 0)
        throw InvalidInput("make_ntriples_chunks: max_triples must be at least 1");
    FirstError errors;
    RaptorWorld world = open_world(errors);
    NTriplesChunks result;
    StringStream stream(world.get(), nullptr);
    parse_turtle(world.get(), errors, text, path, [&](const raptor_statement* st) {
        if (result.num_triples % params.max_triples == 0) {
            result.chunks.emplace_back();
            stream.retarget(&result.chunks.back());
        }
        ++result.num_triples;
        if (st->subject->type == RAPTOR_TERM_TYPE_BLANK ||
            st->object->type == RAPTOR_TERM_TYPE_BLANK)
            result.has_blank_nodes = true;
        if (raptor_statement_ntriples_write(st, stream.get(), 0) != 0 || stream.failed())
            throw IoError("Raptor2 could not write a triple as N-Triples", path);
    });
    return result;
}

// ---------------------------------------------------------------------------------------

struct NQuadsWriter::Impl {
    std::ostream& out;
    FirstError errors;
    RaptorWorld world;
    std::size_t num_documents = 0;
    bool finished = false;

    explicit Impl(std::ostream& o) : out(o), world(open_world(errors)) {}
};

NQuadsWriter::NQuadsWriter(std::ostream& out) : impl_(std::make_unique<Impl>(out)) {}

NQuadsWriter::~NQuadsWriter() = default;

std::size_t NQuadsWriter::add(std::string_view text, const std::string& path,
                              const std::string& graph_iri) {
    Impl& d = *impl_;
    if (d.finished) throw InvalidInput("NQuadsWriter::add after finish");
    validate_iri(graph_iri, "graph IRI");
    raptor_world* world = d.world.get();
    RaptorTerm graph(raptor_new_term_from_counted_uri_string(
        world, reinterpret_cast<const unsigned char*>(graph_iri.data()), graph_iri.size()));
    if (!graph) throw InvalidInput("Raptor2 refuses the graph IRI '" + graph_iri + "'", path);

    // One serializer per document, into a buffer: a document that fails to parse leaves no
    // quad behind. The nquads serializer has no header or footer, so the documents simply
    // follow one another.
    std::string buffer;
    StringStream stream(world, &buffer);
    RaptorSerializer serializer(raptor_new_serializer(world, "nquads"));
    if (!serializer) throw IoError("Raptor2 has no nquads serializer");
    if (raptor_serializer_start_to_iostream(serializer.get(), nullptr, stream.get()) != 0)
        throw IoError("Raptor2 cannot start the nquads serializer");
    const std::string prefix = "d" + std::to_string(d.num_documents) + "_";
    std::size_t count = 0;
    auto relabel = [&](raptor_term* term) -> RaptorTerm {
        if (term->type != RAPTOR_TERM_TYPE_BLANK) return RaptorTerm(raptor_term_copy(term));
        const std::string label =
            prefix + std::string(reinterpret_cast<const char*>(term->value.blank.string),
                                 term->value.blank.string_len);
        return RaptorTerm(raptor_new_term_from_counted_blank(
            world, reinterpret_cast<const unsigned char*>(label.data()), label.size()));
    };
    parse_turtle(world, d.errors, text, path, [&](const raptor_statement* st) {
        RaptorTerm s = relabel(st->subject), p(raptor_term_copy(st->predicate)),
                   o = relabel(st->object), g(raptor_term_copy(graph.get()));
        if (!s || !p || !o || !g) throw IoError("Raptor2: out of memory", path);
        // The statement takes the terms over.
        raptor_statement* quad = raptor_new_statement_from_nodes(world, s.release(), p.release(),
                                                                 o.release(), g.release());
        if (!quad) throw IoError("Raptor2: out of memory", path);
        const int rc = raptor_serializer_serialize_statement(serializer.get(), quad);
        raptor_free_statement(quad);
        if (rc != 0 || stream.failed()) throw IoError("Raptor2 could not write a quad", path);
        ++count;
    });
    if (raptor_serializer_serialize_end(serializer.get()) != 0 || stream.failed())
        throw IoError("Raptor2 could not finish the N-Quads of the document", path);
    serializer.reset();
    d.out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    if (!d.out) throw IoError("cannot write the N-Quads output");
    ++d.num_documents;
    return count;
}

void NQuadsWriter::finish() {
    impl_->finished = true;
    impl_->out.flush();
    if (!impl_->out) throw IoError("cannot write the N-Quads output");
}

}  // namespace geotex
