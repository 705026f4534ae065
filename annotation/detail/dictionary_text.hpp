#pragma once
// The text rules of the dictionary format and the helpers of its messages, apart from the
// checker that walks the YAML (annotation/dictionary.cpp): typo suggestions, ids, control
// characters, namespace IRIs and decimal bounds. Internal to annotation/; each definition
// says more.

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace geotex::dictionary_detail {

/// Optimal string alignment distance (Levenshtein plus transpositions).
size_t edit_distance(std::string_view a, std::string_view b);

/// The name paired with the spelling closest to `word`, when close enough to be a plausible
/// typo; "" otherwise. `candidates`: (spelling to compare with, name to suggest).
std::string closest(const std::string& word,
                    const std::vector<std::pair<std::string, std::string>>& candidates);

/// The words joined by `separator`.
std::string join(const std::vector<std::string>& words, const char* separator = ", ");

/// `s` between single quotes, as the messages name keys and values.
std::string quoted(const std::string& s);

/// An id of the format: a letter or digit, then letters, digits, '-', '_' or '.'.
bool is_id(const std::string& s);

/// First character of `s` that has no place in a text of the dictionary, or -1.
long forbidden_control(const std::string& s, bool multi_line, bool escaped);

/// Why `iri` cannot be a dictionary namespace ("" when it can).
std::string namespace_problem(const std::string& iri);

/// Why `iri` cannot be written whole in RDF, as a creator, licence or match ("" when it can).
std::string iri_problem(const std::string& iri);

/// A YAML number as an xsd:decimal lexical form without exponent; false when not a number.
bool decimal_text(const std::string& s, std::string& out);

}  // namespace geotex::dictionary_detail
