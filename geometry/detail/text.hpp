#pragma once
// Small text helpers shared by the hand-written mesh readers.

#include <string>
#include <string_view>
#include <vector>

namespace geotex::detail {

/// ASCII white space (space, tab, CR, LF, FF, VT).
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

/// A word of a line and its 1-based column.
struct TextToken {
    std::string_view text;
    long column = 0;
};

/// Whitespace-separated tokens of `line`; with `hash_comments`, a '#' ends the line.
std::vector<TextToken> split_tokens(std::string_view line, bool hash_comments);

/// File text quoted in a message: binary garbage escaped as \xNN, cut after 40 bytes.
std::string printable(std::string_view s);

}  // namespace geotex::detail
