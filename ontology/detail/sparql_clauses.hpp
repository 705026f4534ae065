#pragma once
// Clauses of a SPARQL query, taken apart for what geotex runs itself around Rasqal 0.9.33:
// the WHERE clause alone as an ASK, the query without its ORDER BY.

#include <string>

namespace geotex::detail {

/// An ASK query with the prologue and the WHERE clause (and a trailing VALUES clause) of the
/// SELECT `query`: whether the WHERE clause has a solution. Empty when `query` is not a
/// SELECT with a WHERE clause.
std::string where_clause_as_ask(const std::string& query);

/// `query` without the ORDER BY clause of its outermost SELECT (a subquery's stays), line
/// breaks kept; unchanged when it has none.
std::string remove_order_by(const std::string& query);

}  // namespace geotex::detail
