// geotex as a library, the words and the linked data: read a YAML dictionary, print its
// problems or its SKOS concept scheme as Turtle.
//   example_dictionary_skos DICTIONARY.yaml
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "annotation/dictionary.hpp"
#include "common/errors.hpp"
#include "ontology/rdf_writer.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s DICTIONARY.yaml\n", argv[0]);
        return 1;
    }
    std::ifstream in(argv[1], std::ios::binary);
    if (!in) {
        std::fprintf(stderr, "error: %s: cannot open\n", argv[1]);
        return 2;
    }
    std::ostringstream text;
    text << in.rdbuf();
    try {
        const geotex::Dictionary dictionary = geotex::parse_dictionary(text.str(), argv[1]);
        geotex::write_dictionary_rdf(std::cout, dictionary, geotex::RdfFormat::Turtle);
    } catch (const geotex::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.located(argv[1]).c_str());
        return 2;
    }
    return 0;
}
