#pragma once
// The text of a SPARQL query, read before Rasqal 0.9.33 sees it: tokens (SPARQL 1.1's
// lexical rules: IRIs, strings, comments and prefixed names are never mistaken for
// operators), property paths rewritten into the triple patterns and UNIONs that SPARQL 1.1
// defines them as (Rasqal has no property paths), and the WHERE clause alone as an ASK.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace geotex::detail {

struct SparqlToken {
    enum class Kind {
        Iri,           ///< <...>
        PrefixedName,  ///< ex:local, ex:, :local
        Variable,      ///< ?x, $x
        String,        ///< "...", '...', """...""", '''...'''
        Number,        ///< 12, 1.5, .5, 1e3 (a sign is a separate Punct)
        BlankLabel,    ///< _:b1
        LangTag,       ///< @en
        Word,          ///< keywords, `a`, true, false, function names
        Punct,         ///< one- or two-character operators and brackets: { } ( ) [ ] . ; , | / ^ ^^ ...
    };
    Kind kind = Kind::Punct;
    std::size_t begin = 0;  ///< byte offsets into the query
    std::size_t end = 0;
    long line = 1;    ///< 1-based
    long column = 1;  ///< 1-based, in bytes
};

/// The tokens of `query`, comments and white space left out. Never throws on a malformed
/// query (an unterminated string runs to the end): Rasqal reports syntax errors.
std::vector<SparqlToken> tokenize_sparql(std::string_view query);

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

/// An ASK query with the prologue and the WHERE clause (and a trailing VALUES clause) of the
/// SELECT `query`: whether the WHERE clause has a solution. Empty when `query` is not a
/// SELECT with a WHERE clause.
std::string where_clause_as_ask(const std::string& query);

/// `query` without the ORDER BY clause of its outermost SELECT (a subquery's stays), line
/// breaks kept; unchanged when it has none.
std::string remove_order_by(const std::string& query);

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
