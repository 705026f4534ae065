#pragma once
// The writer tests' reading of RDF: Raptor2's own parsers (tests/raptor_reader.hpp) turn the
// output back into plain triples (test_rdf_writer.cpp, test_rdf_honesty.cpp,
// test_dictionary_rdf.cpp).

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "ontology/rdf_writer.hpp"
#include "tests/raptor_reader.hpp"

namespace geotex::test {

inline const std::string kXsd = "http://www.w3.org/2001/XMLSchema#";
inline const std::string kGtx = kGeotexNs;

/// A reading with the checks of a test: one() fails the test unless exactly one triple matches.
struct Parsed : RaptorReading {
    const ParsedTriple& one(const std::string& s, const std::string& p) const {
        const auto all = find(s, p);
        if (all.size() != 1) FAIL("expected one <" << s << "> <" << p << ">, found " << all.size());
        return *all.front();
    }
};

/// The triples of `text` in Raptor2's syntax `syntax` ("turtle", "ntriples", "rdfxml"), with
/// its warnings and errors.
Parsed parse_rdf(const std::string& text, const char* syntax);

/// A file, whole ("" when it cannot be read).
std::string read_file(const std::string& path);

/// write_annotation_rdf into a string.
std::string annotation(const AnnotationDocument& doc, RdfFormat format);

/// write_dictionary_rdf into a string.
std::string dictionary_rdf(const Dictionary& d, RdfFormat format);

}  // namespace geotex::test
