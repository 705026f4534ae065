#pragma once
// ORDER BY, DISTINCT, LIMIT and OFFSET of a SELECT applied by geotex to the rows that Rasqal
// returns, instead of by Rasqal 0.9.33. Rasqal sorts and removes duplicates by inserting
// every row into an unbalanced binary tree (rasqal_map), which rows that arrive already in
// order (every GROUP BY hands its groups over sorted by their keys) turn into a list:
// quadratic (objects-sharing-concept.rq over 100 objects, 54,656 rows: 94 s with ORDER BY
// in Rasqal, 5 s without). The order is Rasqal's own (its comparison function, ties in the
// order the rows came), so the rows are the same; only ORDER BY on projected variables whose
// values are of one kind is taken, any other stays with Rasqal. Include only from .cpp files: it
// brings in rasqal.h.

#include <rasqal.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace geotex::detail {

/// A new reference to `value` as Rasqal 0.9.33 compares it while it runs a query: a typed
/// literal of a datatype it knows (xsd:integer, xsd:double, ...) as a number, a date, a
/// boolean. The values of its results are RDF terms again, a typed literal a string with a
/// datatype, which rasqal_literal_compare orders by its text ("10" before "9"). `value`
/// itself when it is no such literal, or when its text is no value of its datatype.
rasqal_literal* native_literal(rasqal_literal* value);

/// Whether two values are of one kind: one Rasqal type, one datatype and one language.
/// Rasqal's comparison is a strict weak order among values of one kind, not between kinds (a
/// string, a number and an IRI do not compare transitively).
bool same_kind(const rasqal_literal* a, const rasqal_literal* b);

/// The rank of each of `values` (distinct literal objects, of one kind: see same_kind) in
/// rasqal_literal_compare with `flags`, from 0: values that compare equal share a rank, and
/// `tie` says whether any do. False when a comparison fails.
bool rank_literals(const std::vector<rasqal_literal*>& values, int flags, std::vector<int>& ranks,
                   bool& tie);

struct SolutionModifiers {
    std::vector<std::pair<std::size_t, bool>> order;  ///< (projected column, descending)
    bool distinct = false;
    int limit = -1;  ///< -1: none
    int offset = 0;
    bool any() const { return !order.empty() || distinct; }
};

/// The modifiers of the prepared `query` that geotex applies itself: ORDER BY when every key
/// is one of the projected `variables`, DISTINCT (or REDUCED), and then LIMIT and OFFSET,
/// which must come after them. Empty for other queries.
SolutionModifiers plan_solution_modifiers(rasqal_query* query,
                                          const std::vector<std::string>& variables);

/// Turns off in `query` the DISTINCT, LIMIT and OFFSET of `m`. (Rasqal cannot run a query
/// whose ORDER BY keys were removed: the ORDER BY clause goes from the text instead, see
/// remove_order_by in sparql_clauses.hpp.)
void remove_solution_modifiers(rasqal_query* query, const SolutionModifiers& m);

/// The rows of a result as read, with the values of the ORDER BY columns kept as Rasqal's
/// literals for its comparison (native_literal: as its own ORDER BY compares them); frees them.
struct ResultRows {
    std::vector<std::vector<std::string>> cells;
    std::vector<std::vector<std::string>> terms;  ///< N-Triples terms: what DISTINCT compares
    std::vector<std::vector<rasqal_literal*>> keys;
    ResultRows() = default;
    ResultRows(const ResultRows&) = delete;
    ResultRows& operator=(const ResultRows&) = delete;
    ~ResultRows();
};

/// Applies `m` to `rows`: DISTINCT keeps the first of equal rows, then the stable sort, then
/// OFFSET and LIMIT. Returns false, and leaves the rows as they were, when an ORDER BY
/// column mixes kinds of values (numbers and strings, say), whose order only Rasqal's own
/// ORDER BY gives: the caller runs the query again with it.
bool apply_solution_modifiers(const SolutionModifiers& m, ResultRows& rows);

}  // namespace geotex::detail
