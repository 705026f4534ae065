#pragma once
// The triple sinks of the RDF writer (ontology/rdf_writer.cpp): a dry run that writes
// nothing (so that every check fails before the first byte goes out) and Raptor2's serialiser
// writing into a std::ostream. Raptor itself stays in triple_sink.cpp.

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "ontology/rdf_writer.hpp"

namespace geotex::rdf_detail {

struct Prefix {
    const char* prefix;
    const char* ns;
};

struct Term {
    enum class Kind { Iri, Literal } kind = Kind::Iri;
    std::string value;     ///< IRI or lexical form
    std::string datatype;  ///< literal only; empty = xsd:string (or rdf:langString with lang)
    std::string language;  ///< literal only
};

class TripleSink {
  public:
    virtual ~TripleSink() = default;
    virtual void add(const std::string& subject, const std::string& predicate,
                     const Term& object) = 0;
};

/// First pass: nothing is written, so that every InvalidInput is raised before the first byte
/// goes out.
class DryRunSink : public TripleSink {
  public:
    void add(const std::string&, const std::string&, const Term&) override {}
};

/// Second pass: Raptor2's serialiser writing into the std::ostream. Throws IoError.
class RaptorSink : public TripleSink {
  public:
    RaptorSink(std::ostream& out, RdfFormat format, const std::vector<Prefix>& prefixes);
    ~RaptorSink() override;
    RaptorSink(const RaptorSink&) = delete;
    RaptorSink& operator=(const RaptorSink&) = delete;

    void add(const std::string& subject, const std::string& predicate, const Term& object) override;
    /// Ends the serialisation and flushes the stream.
    void finish();

  private:
    class Impl;
    std::unique_ptr<Impl> impl_;  // Raptor keeps pointers into it: it must not move
};

}  // namespace geotex::rdf_detail
