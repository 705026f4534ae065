// UTF-8 and language-tag helpers shared by the dictionary checker, the RDF writer and the
// query result writers. Expected values are from the Unicode Standard, Table 3-7
// (well-formed byte sequences) and BCP 47's tag shape.
#include <catch2/catch.hpp>
#include <string>

#include "common/detail/text.hpp"

using geotex::detail::code_point_name;
using geotex::detail::is_language_tag;
using geotex::detail::utf8_append;
using geotex::detail::utf8_decode;

namespace {
/// Decodes the sequence at the start of `s`: {length, code point}, code point 0 when invalid.
std::pair<std::size_t, char32_t> decode(const std::string& s) {
    char32_t cp = 0;
    const std::size_t n = utf8_decode(s, 0, cp);
    return {n, n == 0 ? char32_t{0} : cp};
}
}  // namespace

TEST_CASE("utf8_decode: well-formed sequences of each length", "[text]") {
    CHECK(decode("A") == std::pair<std::size_t, char32_t>{1, U'A'});
    CHECK(decode("\xC3\xA9") == std::pair<std::size_t, char32_t>{2, 0xE9});
    CHECK(decode("\xE6\xBC\xA2") == std::pair<std::size_t, char32_t>{3, 0x6F22});
    CHECK(decode("\xF0\x9F\x98\x80") == std::pair<std::size_t, char32_t>{4, 0x1F600});
    CHECK(decode("\xF4\x8F\xBF\xBF") == std::pair<std::size_t, char32_t>{4, 0x10FFFF});
    CHECK(decode("\xED\x9F\xBF") == std::pair<std::size_t, char32_t>{3, 0xD7FF});
}

TEST_CASE("utf8_decode: ill-formed sequences give 0", "[text]") {
    for (const std::string bad : {"\x80", "\xBF", "\xC0\xAF", "\xC1\xBF", "\xE0\x80\xAF",
                                  "\xED\xA0\x80", "\xF0\x80\x80\xAF", "\xF4\x90\x80\x80",
                                  "\xF5\x80\x80\x80", "\xFF", "\xC3", "\xE6\xBC", "\xC3\x41"})
        CHECK(decode(bad).first == 0);
}

TEST_CASE("utf8_append: round trip and replacement of non-scalar values", "[text]") {
    for (const char32_t cp : {char32_t{0x41}, char32_t{0xE9}, char32_t{0x6F22}, char32_t{0x1F600},
                              char32_t{0x10FFFF}}) {
        std::string s;
        utf8_append(s, cp);
        char32_t back = 0;
        CHECK(utf8_decode(s, 0, back) == s.size());
        CHECK(back == cp);
    }
    std::string s;
    utf8_append(s, 0xD800);
    utf8_append(s, 0x110000);
    CHECK(s == "\xEF\xBF\xBD\xEF\xBF\xBD");
}

TEST_CASE("code_point_name and is_language_tag", "[text]") {
    CHECK(code_point_name(0x09) == "U+0009");
    CHECK(code_point_name(0x1F600) == "U+1F600");
    for (const char* good : {"en", "fr", "pt-BR", "zh-Hant", "de-CH-1996", "x-private1"})
        CHECK(is_language_tag(good));
    for (const char* bad : {"", "-en", "en-", "e n", "1en", "en--GB", "abcdefghi", "fr\"", "é"})
        CHECK_FALSE(is_language_tag(bad));
    std::string long_tag = "en";
    while (long_tag.size() <= 255) long_tag += "-abcdefgh";
    CHECK_FALSE(is_language_tag(long_tag));
}

TEST_CASE("is_calendar_date: dates that exist, in the Gregorian calendar", "[text]") {
    using geotex::detail::is_calendar_date;
    for (const char* good : {"2026-12-01", "2024-02-29", "2000-02-29", "0001-01-01", "9999-12-31"})
        CHECK(is_calendar_date(good));
    // 1900 and 2100 are not leap years; xsd:date has no year 0000
    for (const char* bad : {"2023-02-29", "1900-02-29", "2100-02-29", "2026-04-31", "2026-13-01",
                            "2026-00-10", "2026-01-00", "0000-01-01", "2026-1-01", "2026/01/01",
                            "2026-01-01Z", "+2026-01-01", "", "２０２６-01-01"})
        CHECK_FALSE(is_calendar_date(bad));
}
