// Raptor2's serialiser behind the RDF writer's triple sink (triple_sink.hpp).

#include "ontology/detail/triple_sink.hpp"

#include <raptor2.h>

#include <exception>

#include "common/errors.hpp"
#include "ontology/detail/raptor_handles.hpp"
#include "ontology/rdf_lexical.hpp"

namespace geotex::rdf_detail {

using detail::RaptorIostream;
using detail::RaptorSerializer;
using detail::RaptorWorld;

class RaptorSink::Impl {
  public:
    Impl(std::ostream& out, RdfFormat format, const std::vector<Prefix>& prefixes)
        : out_(out), escape_controls_(format == RdfFormat::Turtle) {
        raptor_.world.reset(raptor_new_world());
        if (!raptor_.world || raptor_world_open(raptor_.world.get()) != 0)
            fail("cannot start Raptor2");
        raptor_world_set_log_handler(raptor_.world.get(), this, &Impl::log);
        const char* name = format == RdfFormat::Turtle     ? "turtle"
                           : format == RdfFormat::NTriples ? "ntriples"
                                                           : "rdfxml";
        raptor_.serializer.reset(raptor_new_serializer(raptor_.world.get(), name));
        if (!raptor_.serializer.get()) fail(std::string("no Raptor2 serialiser '") + name + "'");
        for (const Prefix& p : prefixes) {
            raptor_uri* ns =
                raptor_new_uri(raptor_.world.get(), reinterpret_cast<const unsigned char*>(p.ns));
            raptor_serializer_set_namespace(raptor_.serializer.get(), ns,
                                            reinterpret_cast<const unsigned char*>(p.prefix));
            raptor_free_uri(ns);
        }
        handler_.version = 2;  // Raptor 2.0.15 refuses a version 1 handler
        handler_.write_byte = &Impl::write_byte;
        handler_.write_bytes = &Impl::write_bytes;
        raptor_.stream.reset(
            raptor_new_iostream_from_handler(raptor_.world.get(), this, &handler_));
        if (!raptor_.stream.get()) fail("cannot create the output stream");
        if (raptor_serializer_start_to_iostream(raptor_.serializer.get(), nullptr,
                                                raptor_.stream.get()) != 0)
            fail("cannot start the serialiser");
        check();
    }

    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    void add(const std::string& subject, const std::string& predicate, const Term& object) {
        raptor_term* s = iri_term(subject);
        raptor_term* p = iri_term(predicate);
        raptor_term* o = nullptr;
        if (object.kind == Term::Kind::Iri) {
            o = iri_term(object.value);
        } else {
            raptor_uri* datatype =
                object.datatype.empty()
                    ? nullptr
                    : raptor_new_uri_from_counted_string(
                          raptor_.world.get(),
                          reinterpret_cast<const unsigned char*>(object.datatype.data()),
                          object.datatype.size());
            o = raptor_new_term_from_counted_literal(
                raptor_.world.get(), reinterpret_cast<const unsigned char*>(object.value.data()),
                object.value.size(), datatype,
                object.language.empty()
                    ? nullptr
                    : reinterpret_cast<const unsigned char*>(object.language.data()),
                static_cast<unsigned char>(object.language.size()));
            if (datatype) raptor_free_uri(datatype);
        }
        if (!s || !p || !o) {
            for (raptor_term* t : {s, p, o})
                if (t) raptor_free_term(t);
            fail("cannot make the terms of a statement about <" + subject + ">");
        }
        raptor_statement* statement =
            raptor_new_statement_from_nodes(raptor_.world.get(), s, p, o, nullptr);
        if (!statement) fail("cannot create a statement");
        const int rc = raptor_serializer_serialize_statement(raptor_.serializer.get(), statement);
        raptor_free_statement(statement);
        if (rc != 0) fail("cannot serialise a statement about <" + subject + ">");
        check();
    }

    void finish() {
        if (raptor_serializer_serialize_end(raptor_.serializer.get()) != 0)
            fail("cannot end the serialisation");
        raptor_.serializer.reset();
        raptor_iostream_write_end(raptor_.stream.get());
        check();
        try {
            flush_buffer();
            out_.flush();
        } catch (const std::exception&) {
            throw IoError("RDF writer: cannot write the output stream");
        }
        if (!out_) throw IoError("RDF writer: cannot write the output stream");
    }

  private:
    raptor_term* iri_term(const std::string& iri) {
        return raptor_new_term_from_counted_uri_string(
            raptor_.world.get(), reinterpret_cast<const unsigned char*>(iri.data()), iri.size());
    }

    [[noreturn]] void fail(const std::string& what) {
        throw IoError("RDF writer: " + what + (error_.empty() ? "" : ": " + error_));
    }

    void check() {
        if (!error_.empty() || failed_silently_) fail("Raptor2 reported an error");
        if (!out_) throw IoError("RDF writer: cannot write the output stream");
    }

    // Raptor's Turtle writer copies a carriage return (and any other control character)
    // into the literal as a raw byte, which Turtle forbids in a short string; in Raptor's
    // Turtle output a raw control byte can only come from a literal, so it is escaped here.
    // Raptor writes many pieces of a few bytes: they are gathered before going to the stream.
    void emit(const char* data, std::size_t size) {
        if (!escape_controls_) {
            buffer_.append(data, size);
        } else {
            for (std::size_t i = 0; i < size; ++i) {
                const auto c = static_cast<unsigned char>(data[i]);
                if (c >= 0x20 || c == '\n' || c == '\t')
                    buffer_ += data[i];
                else
                    buffer_ += c == '\r' ? std::string("\\r") : "\\u00" + hex2(c);
            }
        }
        if (buffer_.size() >= kBufferSize) flush_buffer();
    }

    void flush_buffer() {
        out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
        buffer_.clear();
    }

    // No exception may cross Raptor's C frames: a stream that throws counts as failed.
    int guarded_emit(const char* data, std::size_t size) noexcept {
        try {
            emit(data, size);
        } catch (...) {
            if (error_.empty()) error_ = "the output stream threw an exception";
            return 1;
        }
        return out_ ? 0 : 1;
    }

    static int write_byte(void* context, const int byte) {
        const char c = static_cast<char>(byte);
        return static_cast<Impl*>(context)->guarded_emit(&c, 1);
    }

    static int write_bytes(void* context, const void* ptr, size_t size, size_t nmemb) {
        return static_cast<Impl*>(context)->guarded_emit(static_cast<const char*>(ptr),
                                                         size * nmemb);
    }

    static void log(void* user_data, raptor_log_message* message) {
        auto* self = static_cast<Impl*>(user_data);
        if (message->level < RAPTOR_LOG_LEVEL_ERROR || !self->error_.empty()) return;
        try {
            self->error_ = message->text ? message->text : "unknown error";
        } catch (...) {
            self->failed_silently_ = true;
        }
    }

    std::ostream& out_;
    bool escape_controls_ = false;
    static constexpr std::size_t kBufferSize = 1 << 16;
    std::string buffer_;
    raptor_iostream_handler handler_{};  // Raptor keeps a pointer to it
    std::string error_;
    bool failed_silently_ = false;  ///< an error whose text could not be stored
    // Raptor2 objects, last so freed first, while what their callbacks use still lives; the
    // serialiser before the stream, the world last.
    struct {
        RaptorWorld world;
        RaptorIostream stream;
        RaptorSerializer serializer;
    } raptor_;
};

RaptorSink::RaptorSink(std::ostream& out, RdfFormat format, const std::vector<Prefix>& prefixes)
    : impl_(std::make_unique<Impl>(out, format, prefixes)) {}

RaptorSink::~RaptorSink() = default;

void RaptorSink::add(const std::string& subject, const std::string& predicate, const Term& object) {
    impl_->add(subject, predicate, object);
}

void RaptorSink::finish() { impl_->finish(); }

}  // namespace geotex::rdf_detail
