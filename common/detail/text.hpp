#pragma once
// Small text helpers shared by the hand-written mesh readers, the dictionary checker, the RDF
// writer and the query result writers (UTF-8 is decoded by hand: no Debian library here does
// strict decoding with byte positions for messages).

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace geotex::detail {

/// ASCII white space (space, tab, CR, LF, FF, VT).
inline bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/// The line of `data` that starts at `pos`, without its "\n" or "\r\n"; moves `pos` to the
/// next line. False at the end of the data.
inline bool next_line(std::string_view data, std::size_t& pos, std::string_view& line) {
    if (pos >= data.size()) return false;
    std::size_t end = data.find('\n', pos);
    const bool has_newline = end != std::string_view::npos;
    if (!has_newline) end = data.size();
    line = data.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = has_newline ? end + 1 : end;
    return true;
}

/// A word of a line and its 1-based column.
struct TextToken {
    std::string_view text;
    long column = 0;
};

/// Whitespace-separated tokens of `line`; with `hash_comments`, a '#' ends the line.
std::vector<TextToken> split_tokens(std::string_view line, bool hash_comments);

/// File text quoted in a message: binary garbage escaped as \xNN, cut after 40 bytes.
std::string printable(std::string_view s);

/// User text (file names, option values, YAML keys, values read from files) made safe for a
/// one-line message on a terminal: control characters (C0, DEL, C1), line and paragraph
/// separators and bidirectional overrides are written as visible escapes (\x0a, \u202e),
/// as are bytes that are not UTF-8 (\xe9); everything else, other scripts included, stays
/// as it is. Every message geotex prints goes through it once, where it is printed.
std::string message_text(std::string_view s);

/// Length of the well-formed UTF-8 sequence at s[i] (1 to 4), with its code point in `cp`;
/// 0 when the bytes there are ill-formed (stray continuation byte, truncated sequence,
/// overlong form, surrogate, above U+10FFFF). Requires i < s.size().
std::size_t utf8_decode(std::string_view s, std::size_t i, char32_t& cp);

/// Appends `cp` as UTF-8; U+FFFD for a value that is not a Unicode scalar value.
void utf8_append(std::string& out, char32_t cp);

/// Appends the escape \u00XX of a byte (N-Triples style; for control characters).
void append_u_escape(std::string& out, unsigned char byte);

/// "U+0009", "U+1F600": a code point as messages name it.
std::string code_point_name(char32_t cp);

/// A language tag of the shape BCP 47 gives and Turtle and RDF/XML accept: 1 to 8 ASCII
/// letters, then '-'-separated subtags of 1 to 8 letters or digits ("en", "pt-BR",
/// "zh-Hant"); at most 255 characters (Raptor stores the length in a byte).
bool is_language_tag(std::string_view tag);

/// Byte offset of the first "." or ".." segment in the path of the absolute IRI `iri`
/// ("https://x/a/../b/" gives 12), or npos when there is none. Resolving an IRI (RFC 3986
/// §5.2.4, which every RDF parser does with each IRI it reads) removes such segments, so an
/// IRI that has one reads back as another IRI.
std::size_t find_dot_segment(std::string_view iri);

/// A calendar date YYYY-MM-DD that exists (an xsd:date without time zone): a month of 1 to
/// 12, a day that the month has, 29 February only in a Gregorian leap year, no year 0000.
bool is_calendar_date(std::string_view s);

/// An xsd:dateTime that exists and that the usual RDF tools read back: a calendar date
/// (is_calendar_date: years 0001 to 9999), 'T', hh:mm:ss with hours 00-23, minutes and
/// seconds 00-59 and an optional fraction, then optionally Z or a time zone offset of at most
/// 14:00 either way (+hh:mm, minutes 00-59). Refuses 24:00:00 and leap seconds, which XSD 1.0
/// and 1.1 do not agree on, and years beyond 4 digits or negative.
bool is_date_time(std::string_view s);

}  // namespace geotex::detail
