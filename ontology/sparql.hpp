#pragma once
/// SPARQL over geotex output with Rasqal over an indexed store (embedded, no server).

#include <iosfwd>
#include <string>
#include <vector>

namespace geotex {

enum class ResultFormat { Table, Csv, Json };

/// Bindings of a SELECT, or the answer of an ASK.
struct QueryResult {
    std::vector<std::string> variables;           ///< SELECT variables, in order
    std::vector<std::vector<std::string>> rows;   ///< one string per variable: IRIs as
                                                  ///< <iri>, literals as their lexical form
                                                  ///< (no quotes, datatype or language), ""
                                                  ///< for an unbound variable
    std::vector<std::vector<std::string>> terms;  ///< the same cells as N-Triples terms
    bool is_boolean = false;
    bool boolean_value = false;
};

/// Runs `query` (SPARQL 1.1 as Rasqal 0.9.33 runs it, with what geotex corrects: see
/// ontology/queries/README.md) over the union of the RDF files `data_files` (Turtle,
/// N-Triples, N-Quads or RDF/XML by extension; a set: triples repeated across files count
/// once), read in parallel. Throws ParseError (query syntax with its line; malformed data
/// file with file and line), IoError (missing data file), InvalidInput (CONSTRUCT/DESCRIBE,
/// FROM, the one-variable VALUES form that Rasqal answers wrongly, a property path p*, p+
/// or p?, an unknown data extension, a failure while running).
QueryResult run_sparql(const std::string& query, const std::vector<std::string>& data_files);

/// Writes a result as an aligned text table, CSV (RFC 4180) or SPARQL 1.1 results JSON.
void write_query_result(std::ostream& out, const QueryResult& result, ResultFormat format);

}  // namespace geotex
