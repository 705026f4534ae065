#pragma once
// A YAML text read into a tree that keeps what the dictionary checker needs and yaml-cpp's
// Node API loses: the place (line, column) of every node, duplicate keys, and whether a
// scalar was quoted. Encoding problems, syntax errors, quotes that are never closed and
// extra documents are reported as problems at their place. Internal to annotation/.

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "annotation/dictionary.hpp"
#include "common/detail/text.hpp"

namespace geotex::yaml_detail {

using std::size_t;

constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

/// Maps byte offsets of the text to 1-based lines and columns. Columns count characters
/// (a well-formed UTF-8 sequence or a single ill-formed byte is one column), so they match
/// what editors show for non-ASCII labels; a leading byte order mark takes no column.
class Places {
  public:
    explicit Places(std::string_view text) : text_(text) {
        line_starts_.push_back(0);
        for (size_t i = 0; i < text.size(); ++i)
            if (text[i] == '\n') line_starts_.push_back(i + 1);
    }

    std::pair<long, long> at(size_t offset) const {
        offset = std::min(offset, text_.size());
        const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
        const long line = static_cast<long>(it - line_starts_.begin());
        size_t i = *std::prev(it);
        if (i == 0 && text_.substr(0, kUtf8Bom.size()) == kUtf8Bom)
            i = std::min(offset, kUtf8Bom.size());
        long column = 1;
        while (i < offset) {
            char32_t cp = 0;
            const size_t n = detail::utf8_decode(text_, i, cp);
            i += n == 0 ? 1 : n;
            ++column;
        }
        return {line, column};
    }

  private:
    std::string_view text_;
    std::vector<size_t> line_starts_;
};

/// The problems found so far, each placed by line and column.
struct Problems {
    const Places* places = nullptr;
    std::vector<DictionaryProblem> list;

    void add(size_t offset, std::string message) {
        const auto [line, column] = places->at(offset);
        list.push_back({line, column, std::move(message)});
    }
    long line_of(size_t offset) const { return places->at(offset).first; }
};

struct YNode {
    enum class Kind { Null, Scalar, Sequence, Map };
    Kind kind = Kind::Null;
    size_t offset = 0;       ///< byte offset of the node in the text
    std::string tag;         ///< "?" plain scalar, "!" quoted or block scalar, or an explicit tag
    std::string value;       ///< scalars
    std::vector<int> items;  ///< sequence items; map keys and values alternate
};

/// "nothing", "a single value", "a list", "a map": a node kind as messages name it.
const char* kind_name(YNode::Kind k);

struct YamlTree {
    std::vector<YNode> nodes;
    std::vector<int> roots;  ///< root node of each document (-1 for an empty one)
    /// False after a syntax error or a quote that is never closed: the tree may then hold
    /// less than the curator wrote, and its structure should not be checked.
    bool readable = true;
};

/// Reads `text` (UTF-8, an optional byte order mark) into a tree; reports encoding problems,
/// YAML syntax errors, unterminated quotes and documents after the first into `problems`.
YamlTree read_yaml_tree(std::string_view text, Problems& problems);

}  // namespace geotex::yaml_detail
