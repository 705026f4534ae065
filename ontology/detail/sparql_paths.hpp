#pragma once
// SPARQL 1.1 property paths rewritten into the triple patterns and UNIONs that SPARQL 1.1
// defines them as, for Rasqal 0.9.33, which has no property paths.

#include <string>

namespace geotex::detail {

/// `query` with every property path of a triple pattern rewritten as SPARQL 1.1 translates it
/// (§18.2.2.4): a sequence p/q into two patterns joined by a new variable, an inverse ^p into
/// the pattern with subject and object swapped, an alternative p|q into a UNION, a negated
/// set !(p|^q) into a pattern on a new predicate variable with a FILTER. New variables are
/// named `fresh_prefix` followed by a number (a prefix no variable of the query starts
/// with). Line breaks are kept, so that Rasqal's messages give the user's lines. The query
/// comes back unchanged when it has no property path. Throws InvalidInput (with line and
/// column) for p?, p* and p+, which no finite rewriting expresses, and for a path in a
/// pattern whose subject or object is a [ ... ] or ( ... ) node.
std::string rewrite_property_paths(const std::string& query, std::string* fresh_prefix);

}  // namespace geotex::detail
