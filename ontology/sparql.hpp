#pragma once
/// SPARQL over geotex output with Rasqal over an indexed store (embedded, no server).

#include <iosfwd>
#include <string>
#include <vector>

#include "common/errors.hpp"

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

/// How a query runs.
struct QueryParams {
    double timeout = 0;  ///< seconds of wall time for reading the data and running the query;
                         ///< 0: no limit (finite and >= 0)
};

/// A query that ran out of its QueryParams::timeout. Nothing of its result is kept.
class QueryTimeout : public Error {
  public:
    using Error::Error;
};

/// Runs `query` (SPARQL 1.1 as Rasqal 0.9.33 runs it, with what geotex corrects: see
/// ontology/queries/README.md) over the union of the RDF files `data_files` (Turtle,
/// N-Triples, N-Quads or RDF/XML by extension; a set: triples repeated across files count
/// once), read in parallel. Throws ParseError (query syntax with its line; malformed data
/// file with file and line), IoError (missing data file), InvalidInput (CONSTRUCT/DESCRIBE,
/// FROM, SERVICE (with the line and column of its keyword: a query never reads anything but
/// the data files), the one-variable VALUES form that Rasqal answers wrongly, a property
/// path p*, p+ or p?, an unknown data extension, a timeout that is negative or not finite,
/// a failure while running), QueryTimeout. A UTF-8 byte order mark at the start of `query`
/// is skipped.
QueryResult run_sparql(const std::string& query, const std::vector<std::string>& data_files,
                       const QueryParams& params = {});

/// Writes a result as an aligned text table, CSV (RFC 4180) or SPARQL 1.1 results JSON.
void write_query_result(std::ostream& out, const QueryResult& result, ResultFormat format);

}  // namespace geotex
