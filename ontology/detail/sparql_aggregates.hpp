#pragma once
// Aggregates that Rasqal 0.9.33 gets wrong, written the way it gets right (COUNT(?x),
// GROUP_CONCAT with a SEPARATOR), and what geotex then does to the rows.

#include <string>
#include <vector>

namespace geotex::detail {

/// A projected GROUP_CONCAT whose SEPARATOR geotex applies itself (see rewrite_aggregates).
struct ConcatColumn {
    std::string variable;   ///< the projected variable, without '?'
    std::string separator;  ///< the SEPARATOR string, unescaped
};

/// `query` with two aggregates of Rasqal 0.9.33 written the way it gets right, exactly:
/// - COUNT(?x) (of one variable, without DISTINCT), which Rasqal counts also where ?x is
///   unbound, becomes SUM(IF(BOUND(?x), 1, 0));
/// - a projected (GROUP_CONCAT(expr; SEPARATOR="s") AS ?v) without DISTINCT, whose
///   separator Rasqal ignores (it always joins with a space), becomes
///   (GROUP_CONCAT(IF(STR(expr) = "", "%", ENCODE_FOR_URI(STR(expr)))) AS ?v): its parts
///   hold no space and are never empty (Rasqal gives no value for an empty concatenation;
///   a lone "%" is never an encoded text), and
///   `concat_columns` says which columns to split, decode and join with "s" (not done for a
///   column that ORDER BY sorts by, which would sort by the encoded text).
/// Line breaks are kept. Unchanged when there is nothing to rewrite.
std::string rewrite_aggregates(const std::string& query, std::vector<ConcatColumn>* concat_columns);

/// The value of a GROUP_CONCAT column rewritten by rewrite_aggregates: the percent-encoded
/// parts that Rasqal joined with spaces ("%" for ""), decoded and joined with `separator`.
std::string join_concat_parts(const std::string& joined, const std::string& separator);

}  // namespace geotex::detail
