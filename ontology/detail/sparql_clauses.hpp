#pragma once
// Clauses of a SPARQL query, taken apart for what geotex runs itself around Rasqal 0.9.33:
// the WHERE clause alone as an ASK, the query without its ORDER BY, the rows of a GROUP BY
// before grouping.

#include <string>
#include <vector>

namespace geotex::detail {

/// An ASK query with the prologue and the WHERE clause (and a trailing VALUES clause) of the
/// SELECT `query`: whether the WHERE clause has a solution. Empty when `query` is not a
/// SELECT with a WHERE clause.
std::string where_clause_as_ask(const std::string& query);

/// `query` without the ORDER BY clause of its outermost SELECT (a subquery's stays), line
/// breaks kept; unchanged when it has none.
std::string remove_order_by(const std::string& query);

/// The outermost SELECT of `query` projecting `variables` (names without '?') from its WHERE
/// clause as it is, without DISTINCT or REDUCED and without its solution modifiers (GROUP
/// BY, HAVING, ORDER BY, LIMIT, OFFSET); a trailing VALUES clause is kept, and so are the
/// line breaks. Empty when `query` is not a SELECT with a WHERE clause.
std::string ungrouped_select(const std::string& query, const std::vector<std::string>& variables);

}  // namespace geotex::detail
