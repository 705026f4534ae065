#pragma once
/// Turtle re-written for triple stores (Raptor2): as N-Triples cut into chunks, for Graph
/// Store uploads that a store takes in several requests, and as N-Quads in named graphs, for
/// bulk loaders.

#include <cstddef>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace geotex {

struct NTriplesChunkParams {
    std::size_t max_triples = 100000;  ///< triples per chunk (>= 1); Virtuoso can hang on
                                       ///< one upload of tens of MB (about 100k triples)
};

/// The triples of one Turtle document as N-Triples documents.
struct NTriplesChunks {
    std::vector<std::string> chunks;  ///< N-Triples, at most max_triples lines each, in
                                      ///< document order; none for an empty document
    std::size_t num_triples = 0;      ///< statements read (a repeated triple counts each time)
    bool has_blank_nodes = false;     ///< a store reads the blank nodes of two chunks as
                                      ///< different nodes (geotex output has none)
};

/// Parses the Turtle `text` of `path` (which names it in messages and is its base IRI, as
/// `geotex query` reads files) and returns its triples as N-Triples chunks. Throws
/// ParseError (file, line, column) on invalid Turtle, InvalidInput when max_triples is 0.
NTriplesChunks make_ntriples_chunks(std::string_view text, const std::string& path,
                                    const NTriplesChunkParams& params = {});

/// Writes Turtle documents as one N-Quads stream (Raptor2's nquads serializer): each
/// document's triples in the named graph given with it, in document order, documents in the
/// order added, so the same documents give the same bytes. Blank node labels get a prefix
/// per document ("d3_b1"): equal labels of two documents stay two nodes.
class NQuadsWriter {
  public:
    /// Starts the stream. Throws IoError when Raptor2 cannot start.
    explicit NQuadsWriter(std::ostream& out);
    NQuadsWriter(const NQuadsWriter&) = delete;
    NQuadsWriter& operator=(const NQuadsWriter&) = delete;
    ~NQuadsWriter();

    /// Adds the triples of the Turtle `text` of `path` in the graph `graph_iri` (an
    /// absolute IRI: validate_iri) and returns how many. Throws ParseError on invalid Turtle
    /// (nothing of that document is written then, so the caller may go on with the next),
    /// InvalidInput on a bad graph IRI, IoError when the output fails.
    std::size_t add(std::string_view text, const std::string& path, const std::string& graph_iri);

    /// Ends the stream and flushes it. Throws IoError when the output fails.
    void finish();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace geotex
