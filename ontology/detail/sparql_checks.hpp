#pragma once
// What `geotex query` refuses in a query before running it: what Rasqal 0.9.33 would run
// wrongly without saying so, and what would make it read anything but the data files.
// Include only from .cpp files: it brings in rasqal.h.

#include <rasqal.h>

#include <string>

namespace geotex::detail {

/// Throws InvalidInput (with line and column) at the first SERVICE keyword: Rasqal would
/// fetch its IRI, over the network (and hang on a host that never answers) or from a local
/// file. Strings, comments, IRIs and prefixed names are no keywords.
void refuse_service(const std::string& query);

/// Throws InvalidInput at the first keyword of SPARQL 1.1 Update (LOAD, INSERT, DELETE, ...).
void refuse_updates(const std::string& query);

/// Whether a parsed graph pattern or one of its sub-patterns is a SERVICE (a second guard
/// behind refuse_service, on what Rasqal parsed).
bool has_service(rasqal_graph_pattern* gp);

/// Throws InvalidInput (with line and column) at the first one-variable `VALUES ?x { ... }`
/// block: Rasqal 0.9.33 returns only the first value's rows for it inside a pattern and
/// crashes on it after the WHERE clause.
void check_values_form(const std::string& query);

/// Whether the query has the keyword MINUS (which fails in Rasqal 0.9.33 when it runs): for
/// the error message.
bool mentions_minus(const std::string& query);

}  // namespace geotex::detail
