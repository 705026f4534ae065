#pragma once
// The data of `geotex query`: the RDF files read with Raptor2 into one TripleStore, a set (a
// triple written twice, in one file or in two, matches once, as the SPARQL dataset is a set).

#include <string>
#include <vector>

#include "ontology/detail/query_deadline.hpp"
#include "ontology/detail/triple_store.hpp"

namespace geotex::detail {

/// Reads `files` (Turtle, N-Triples, N-Quads or RDF/XML by extension) into `store` and
/// finishes it. The files are parsed in parallel (as many threads as TBB may use, no more
/// than files), each into a store of its own, merged in the order given, so that the terms'
/// ids do not depend on the threads. A failure is that of the first failing file in that
/// order: IoError (missing, a directory), ParseError (with file, line and column),
/// InvalidInput (an unknown extension), QueryTimeout once `deadline` has passed. Blank node
/// labels are renumbered per file; a literal's \u0000 escapes are kept (Raptor 2.0.15 cuts
/// the value there).
void load_data(const std::vector<std::string>& files, TripleStore& store, const Deadline& deadline);

}  // namespace geotex::detail
