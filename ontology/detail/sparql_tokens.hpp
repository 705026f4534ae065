#pragma once
// The tokens of a SPARQL query, read before Rasqal 0.9.33 sees it (SPARQL 1.1's lexical
// rules: IRIs, strings, comments and prefixed names are never mistaken for operators or
// keywords), and text edits on the query that keep its line breaks, so that Rasqal's
// messages give the user's lines.

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
        Punct,  ///< one- or two-character operators and brackets: { } ( ) [ ] . ; , | / ^ ^^ ...
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

/// The text of a token.
inline std::string_view token_text(std::string_view query, const SparqlToken& t) {
    return query.substr(t.begin, t.end - t.begin);
}
/// Whether a token is the keyword `upper` (given in upper case), in any case.
bool is_keyword(std::string_view query, const SparqlToken& t, std::string_view upper);
/// Whether a token is the punctuation `p`.
inline bool is_punct(std::string_view query, const SparqlToken& t, std::string_view p) {
    return t.kind == SparqlToken::Kind::Punct && token_text(query, t) == p;
}

/// A replacement of the bytes [begin, end) of a query.
struct TextEdit {
    std::size_t begin = 0, end = 0;
    std::string text;
};
/// `query` with `edits` (which must not overlap) applied.
std::string apply_edits(const std::string& query, std::vector<TextEdit> edits);
/// `n` line breaks, n being the number in the bytes [begin, end) of `query`: appended to a
/// replacement, they keep the lines after it where they were.
std::string line_breaks(std::string_view query, std::size_t begin, std::size_t end);

}  // namespace geotex::detail
