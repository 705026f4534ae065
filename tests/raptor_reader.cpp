#include "tests/raptor_reader.hpp"

#include <raptor2.h>

namespace geotex::test {

namespace {

std::string term_text(const raptor_term* term, RaptorReading& reading) {
    switch (term->type) {
        case RAPTOR_TERM_TYPE_URI:
            return reinterpret_cast<const char*>(raptor_uri_as_string(term->value.uri));
        case RAPTOR_TERM_TYPE_LITERAL:
            return std::string(reinterpret_cast<const char*>(term->value.literal.string),
                               term->value.literal.string_len);
        default:
            ++reading.blank_nodes;
            return "_:";
    }
}

}  // namespace

std::vector<const ParsedTriple*> RaptorReading::find(const std::string& s,
                                                     const std::string& p) const {
    std::vector<const ParsedTriple*> out;
    for (const auto& t : triples)
        if (t.s == s && t.p == p) out.push_back(&t);
    return out;
}

std::set<std::string> RaptorReading::subjects_of_type(const std::string& cls) const {
    std::set<std::string> out;
    for (const auto& t : triples)
        if (t.p == kRdfType && t.o == cls) out.insert(t.s);
    return out;
}

RaptorReading read_with_raptor(const std::string& text, const char* syntax) {
    RaptorReading reading;
    raptor_world* world = raptor_new_world();
    if (!world || raptor_world_open(world) != 0) {
        reading.errors.push_back("Raptor2 does not start");
        if (world) raptor_free_world(world);
        return reading;
    }
    raptor_world_set_log_handler(world, &reading, [](void* user, raptor_log_message* m) {
        if (m->level >= RAPTOR_LOG_LEVEL_WARN)
            static_cast<RaptorReading*>(user)->errors.push_back(m->text ? m->text : "?");
    });
    raptor_parser* parser = raptor_new_parser(world, syntax);
    if (!parser) {
        reading.errors.push_back(std::string("Raptor2 has no parser ") + syntax);
        raptor_free_world(world);
        return reading;
    }
    raptor_parser_set_statement_handler(parser, &reading, [](void* user, raptor_statement* st) {
        auto& r = *static_cast<RaptorReading*>(user);
        ParsedTriple t;
        t.s = term_text(st->subject, r);
        t.p = term_text(st->predicate, r);
        t.o = term_text(st->object, r);
        if (st->object->type == RAPTOR_TERM_TYPE_LITERAL) {
            t.literal = true;
            if (st->object->value.literal.datatype)
                t.datatype = reinterpret_cast<const char*>(
                    raptor_uri_as_string(st->object->value.literal.datatype));
            if (st->object->value.literal.language)
                t.language = reinterpret_cast<const char*>(st->object->value.literal.language);
        }
        r.triples.push_back(std::move(t));
    });
    raptor_uri* base =
        raptor_new_uri(world, reinterpret_cast<const unsigned char*>("http://base.invalid/"));
    raptor_parser_parse_start(parser, base);
    raptor_parser_parse_chunk(parser, reinterpret_cast<const unsigned char*>(text.data()),
                              text.size(), 1);
    raptor_free_uri(base);
    raptor_free_parser(parser);
    raptor_free_world(world);
    return reading;
}

}  // namespace geotex::test
