#pragma once
// Dictionaries and helpers shared by the dictionary tests (test_dictionary.cpp,
// test_dictionary_facets.cpp, test_default_dictionary.cpp).

#include <string>
#include <vector>

#include "annotation/dictionary.hpp"

namespace geotex::test {

/// A small clean dictionary without facets; its places are commented in the definition.
extern const std::string kClean;
/// The same kind of dictionary with facets and relief; its places are commented likewise.
extern const std::string kFaceted;

/// `text` with the one occurrence of `from` replaced by `to` (REQUIREs that it occurs once).
std::string edit(std::string text, const std::string& from, const std::string& to);

/// The problems as "line:column: message" lines.
std::string listing(const std::vector<DictionaryProblem>& problems);

/// The text has exactly one problem, at line:column, whose message contains `fragment`.
void require_one(const std::string& text, long line, long column, const std::string& fragment);

/// One broken copy of a dictionary: `from` replaced by `to`, and the one problem expected.
struct ExpectedProblem {
    std::string from, to;  ///< the edit (edit() below)
    long line = 0, column = 0;
    std::string fragment;  ///< a part of the message
};

/// require_one for each edit of `text`, each checked on its own (the edit in the INFO).
void require_each(const std::string& text, const std::vector<ExpectedProblem>& cases);

/// A file of the repository, whole.
std::string read_source_file(const std::string& relative);

/// dictionaries/default.yaml, parsed once for the whole test run.
const Dictionary& default_dictionary();

/// Lower-case letters and digits in words joined by single hyphens ("flat-region-pca3").
bool is_kebab_case(const std::string& id);

/// Column of a feature id (REQUIREs that it is known).
int column_of(const char* id);

}  // namespace geotex::test
