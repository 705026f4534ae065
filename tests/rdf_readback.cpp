#include "tests/rdf_readback.hpp"

#include <raptor2.h>

#include <fstream>
#include <sstream>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define GEOTEX_LSAN_SCOPE __lsan::ScopedDisabler raptor_parser_leaks
#else
#define GEOTEX_LSAN_SCOPE
#endif

namespace geotex::test {

namespace {

std::string term_text(raptor_term* term, Parsed& parsed) {
    switch (term->type) {
        case RAPTOR_TERM_TYPE_URI:
            return reinterpret_cast<const char*>(raptor_uri_as_string(term->value.uri));
        case RAPTOR_TERM_TYPE_LITERAL:
            return std::string(reinterpret_cast<const char*>(term->value.literal.string),
                               term->value.literal.string_len);
        default:
            ++parsed.blank_nodes;
            return "_:";
    }
}

}  // namespace

Parsed parse_rdf(const std::string& text, const char* syntax) {
    // Raptor 2.0.15's N-Triples parser leaks the datatype URI of every typed literal (and so
    // the world's own URIs that it references); those leaks are Raptor's, not the writer's.
    GEOTEX_LSAN_SCOPE;
    Parsed parsed;
    raptor_world* world = raptor_new_world();
    raptor_world_open(world);
    raptor_world_set_log_handler(world, &parsed, [](void* user, raptor_log_message* m) {
        if (m->level >= RAPTOR_LOG_LEVEL_WARN)
            static_cast<Parsed*>(user)->errors.push_back(m->text ? m->text : "?");
    });
    raptor_parser* parser = raptor_new_parser(world, syntax);
    raptor_parser_set_statement_handler(parser, &parsed, [](void* user, raptor_statement* st) {
        auto& p = *static_cast<Parsed*>(user);
        ParsedTriple t;
        t.s = term_text(st->subject, p);
        t.p = term_text(st->predicate, p);
        t.o = term_text(st->object, p);
        if (st->object->type == RAPTOR_TERM_TYPE_LITERAL) {
            t.literal = true;
            if (st->object->value.literal.datatype)
                t.datatype = reinterpret_cast<const char*>(
                    raptor_uri_as_string(st->object->value.literal.datatype));
            if (st->object->value.literal.language)
                t.language = reinterpret_cast<const char*>(st->object->value.literal.language);
        }
        p.triples.push_back(t);
    });
    raptor_uri* base =
        raptor_new_uri(world, reinterpret_cast<const unsigned char*>("http://base.invalid/"));
    raptor_parser_parse_start(parser, base);
    raptor_parser_parse_chunk(parser, reinterpret_cast<const unsigned char*>(text.data()),
                              text.size(), 1);
    raptor_free_uri(base);
    raptor_free_parser(parser);
    raptor_free_world(world);
    return parsed;
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string annotation(const AnnotationDocument& doc, RdfFormat format) {
    std::ostringstream out;
    write_annotation_rdf(out, doc, format);
    return out.str();
}

std::string dictionary_rdf(const Dictionary& d, RdfFormat format) {
    std::ostringstream out;
    write_dictionary_rdf(out, d, format);
    return out.str();
}

}  // namespace geotex::test
