#pragma once
// The order of the triple patterns of a basic graph pattern, chosen before Rasqal 0.9.33 sees
// the query: Rasqal matches them in the order written, once for every row of the patterns
// before, and never reorders them.

#include <functional>
#include <string>

namespace geotex::detail {

/// The expected number of triples that match a pattern with predicate `predicate` (an
/// absolute IRI; empty for a variable or an IRI that cannot be resolved), given whether its
/// subject and object are fixed (a constant, or a variable that an earlier pattern bound).
using PatternCost =
    std::function<double(const std::string& predicate, bool subject_fixed, bool object_fixed)>;

/// `query` with the triple patterns of each group that holds nothing but triple patterns and
/// FILTERs reordered: the patterns keep their written order, except that a pattern that
/// matches at most one triple on average once its subject or object is fixed (`cost` <= 1:
/// a functional property such as dcterms:identifier of a mesh) moves to just after the
/// patterns that fix it, so that it is matched once per row of those rather than once per
/// row of every pattern written before it. The solutions are the same (a basic graph pattern
/// is a set of patterns); without ORDER BY the rows may come in another order. FILTERs follow
/// the patterns. Line breaks are kept; comments inside a reordered group are dropped. The
/// query comes back unchanged when nothing moves or a group is not read (Rasqal reads it).
std::string order_triple_patterns(const std::string& query, const PatternCost& cost);

}  // namespace geotex::detail
