#pragma once
// An independent reading of RDF: Raptor2's own parsers turn a text back into plain triples.
// Shared by the writer tests (tests/rdf_readback.hpp) and the RDF fuzz target
// (fuzz/fuzz_rdf_strings.cpp), so free of any test framework.

#include <set>
#include <string>
#include <vector>

namespace geotex::test {

inline const std::string kRdfType = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type";

struct ParsedTriple {
    std::string s, p, o;  ///< IRIs and literal values as text; a blank node is "_:"
    bool literal = false;
    std::string datatype, language;
};

struct RaptorReading {
    std::vector<ParsedTriple> triples;
    std::vector<std::string> errors;  ///< Raptor's warnings and errors
    int blank_nodes = 0;              ///< blank-node terms seen, in any position

    /// The triples with subject `s` and predicate `p`, in the order read.
    std::vector<const ParsedTriple*> find(const std::string& s, const std::string& p) const;
    /// The subjects of rdf:type `cls`.
    std::set<std::string> subjects_of_type(const std::string& cls) const;
};

/// The triples of `text` in Raptor2's syntax `syntax` ("turtle", "ntriples", "rdfxml"), with
/// its warnings and errors; relative IRIs resolve against http://base.invalid/.
RaptorReading read_with_raptor(const std::string& text, const char* syntax);

}  // namespace geotex::test
