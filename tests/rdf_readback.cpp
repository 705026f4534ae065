#include "tests/rdf_readback.hpp"

#include <fstream>
#include <sstream>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define GEOTEX_LSAN_SCOPE __lsan::ScopedDisabler raptor_parser_leaks
#else
#define GEOTEX_LSAN_SCOPE
#endif

namespace geotex::test {

Parsed parse_rdf(const std::string& text, const char* syntax) {
    // Raptor 2.0.15's N-Triples parser leaks the datatype URI of every typed literal (and so
    // the world's own URIs that it references); those leaks are Raptor's, not the writer's.
    GEOTEX_LSAN_SCOPE;
    Parsed parsed;
    static_cast<RaptorReading&>(parsed) = read_with_raptor(text, syntax);
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
