#pragma once
/// Edits of a dictionary's YAML text that change only the edited spans: a curator's bound
/// moves and label changes (the workbench, `geotex dict fit`), and the stamp of a new version.
/// Comments, key order, quoting style, CRLF line ends and a UTF-8 byte order mark are kept.

#include <string>
#include <string_view>
#include <vector>

#include "annotation/dictionary.hpp"

namespace geotex {

/// One edit of a concept: move a bound of its interval, or set its label in a language.
struct DictionaryEdit {
    enum class Kind { Bound, Label };
    Kind kind = Kind::Bound;
    std::string concept_id;
    bool upper = false;    ///< Bound: the upper (true) or lower (false) bound
    std::string language;  ///< Label: language tag
    std::string value;     ///< Bound: decimal text, ".inf"/"-.inf" allowed; Label: the new label
};

/// The edited text and what is wrong with the edits or with the text they make.
struct DictionaryEditResult {
    std::string text;  ///< the edited YAML (the edits that could not apply are left out)
    /// Problems of the edits (line 0 when the edit has no place in the text: an unknown
    /// concept) followed by check_dictionary(text); empty when the result is clean.
    std::vector<DictionaryProblem> problems;
};

/// Applies `edits` in order to `yaml_text`. A bound shared with the neighbouring interval of
/// the same feature (the upper bound of one written as the lower bound of the other, compared
/// as decimals, so 0.05 and 5e-2 are one bound) moves both. A bound is written as given; a
/// label keeps the quoting style of the label it replaces, quoted when YAML needs it, and a
/// label in a new language is added to the concept's `labels` map. Edits of a text that does
/// not read as YAML are not applied (its problems are returned). Never throws on bad edits:
/// each is a problem ("edit 2: ...").
DictionaryEditResult edit_dictionary(std::string_view yaml_text,
                                     const std::vector<DictionaryEdit>& edits);

/// The text with scheme.version bumped and scheme.modified set to `today` (YYYY-MM-DD; the
/// key is added after `version` when absent), only those spans changed. The bump increases
/// the last number of the version by one ("2.0" -> "2.1", "2.9" -> "2.10", "v7" -> "v8");
/// a version without digits gets ".1" appended (dictionaries/README.md, "Versions").
/// Throws InvalidInput when `today` is not a date or the text has no scheme.version scalar.
std::string stamp_new_version(std::string_view yaml_text, std::string_view today);

/// The version that follows `version` under stamp_new_version's rule.
std::string next_version(std::string_view version);

}  // namespace geotex
