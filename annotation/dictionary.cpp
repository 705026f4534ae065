#include "annotation/dictionary.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "annotation/detail/dictionary_checker.hpp"
#include "annotation/detail/dictionary_text.hpp"
#include "annotation/digest.hpp"
#include "annotation/yaml_tree.hpp"
#include "common/detail/text.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"

namespace geotex {

const DictionaryConcept* Dictionary::find(int feature, double value) const {
    if (std::isnan(value)) return nullptr;
    // concepts are sorted by (feature, lower) and the intervals of one feature are disjoint,
    // so the candidate is the last concept of the feature whose lower bound is <= value.
    const auto by_feature_then_lower = [](const DictionaryConcept& c,
                                          const std::pair<int, double>& key) {
        return c.feature < key.first || (c.feature == key.first && c.lower <= key.second);
    };
    const auto after = std::lower_bound(concepts.begin(), concepts.end(),
                                        std::make_pair(feature, value), by_feature_then_lower);
    if (after == concepts.begin()) return nullptr;
    const DictionaryConcept& c = *std::prev(after);
    if (c.feature != feature || !(c.lower <= value && value < c.upper)) return nullptr;
    return &c;
}

namespace {

using namespace yaml_detail;
using dictionary_detail::Checker;

struct Analysis {
    Dictionary dictionary;
    std::vector<DictionaryProblem> problems;
};

Analysis analyse(std::string_view text) {
    Analysis a;
    const Places places(text);
    Problems problems{&places, {}};
    const YamlTree tree = read_yaml_tree(text, problems);
    Checker checker(text, tree.nodes, problems);
    checker.check_duplicate_keys();
    // The structure is checked only on a tree that is what the curator wrote: after a syntax
    // error or a runaway quote, missing keys would be consequences, not problems of their own.
    if (tree.readable) {
        if (tree.roots.empty()) {
            problems.add(0,
                         "empty dictionary: expected a map with the keys 'scheme' and 'features'");
        } else {
            checker.check_document(tree.roots[0], a.dictionary);
        }
    }
    a.problems = std::move(problems.list);
    a.dictionary.warnings = std::move(checker.warnings);
    std::stable_sort(a.dictionary.warnings.begin(), a.dictionary.warnings.end(),
                     [](const DictionaryProblem& x, const DictionaryProblem& y) {
                         return x.line != y.line ? x.line < y.line : x.column < y.column;
                     });
    std::stable_sort(a.problems.begin(), a.problems.end(),
                     [](const DictionaryProblem& x, const DictionaryProblem& y) {
                         return x.line != y.line ? x.line < y.line : x.column < y.column;
                     });
    return a;
}

}  // namespace

std::vector<DictionaryProblem> check_dictionary(std::string_view yaml_text) {
    return analyse(yaml_text).problems;
}

Dictionary parse_dictionary(std::string_view yaml_text, const std::string& name) {
    Analysis a = analyse(yaml_text);
    if (!a.problems.empty()) {
        const DictionaryProblem& first = a.problems.front();
        std::string what = "dictionary: " + first.message;
        if (a.problems.size() > 1)
            what += " (and " + std::to_string(a.problems.size() - 1) + " more problem" +
                    (a.problems.size() > 2 ? "s" : "") + "; 'geotex dict check' lists them all)";
        throw ParseError(what, name, first.line, first.column);
    }
    a.dictionary.sha256 = sha256_hex(yaml_text);
    a.dictionary.source_name = name;
    return std::move(a.dictionary);
}

}  // namespace geotex
