#include "common/detail/text.hpp"

#include <algorithm>
#include <cstdio>

namespace geotex::detail {

std::vector<TextToken> split_tokens(std::string_view line, bool hash_comments) {
    std::vector<TextToken> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        if (i >= line.size() || (hash_comments && line[i] == '#')) break;
        const std::size_t start = i;
        while (i < line.size() && !is_space(line[i]) && !(hash_comments && line[i] == '#')) ++i;
        tokens.push_back({line.substr(start, i - start), static_cast<long>(start) + 1});
    }
    return tokens;
}

std::string printable(std::string_view s) {
    std::string out;
    for (char c : s.substr(0, 40)) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 32 && u < 127) {
            out += c;
        } else {
            static const char hex[] = "0123456789abcdef";
            out += "\\x";
            out += hex[u >> 4];
            out += hex[u & 15];
        }
    }
    if (s.size() > 40) out += "...";
    return out;
}

std::string message_text(std::string_view s) {
    static const char hex[] = "0123456789abcdef";
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size();) {
        char32_t cp = 0;
        const std::size_t len = utf8_decode(s, i, cp);
        if (len == 0 || cp < 0x20 || cp == 0x7f) {  // a control byte, or not UTF-8
            const auto u = static_cast<unsigned char>(s[i]);
            out += "\\x";
            out += hex[u >> 4];
            out += hex[u & 15];
            ++i;
            continue;
        }
        // C1 controls (U+0085 is a line break to some terminals), separators, bidi controls
        // (which reorder the rest of the line as displayed).
        const bool invisible = (cp >= 0x80 && cp <= 0x9f) || cp == 0x2028 || cp == 0x2029 ||
                               (cp >= 0x202a && cp <= 0x202e) || (cp >= 0x2066 && cp <= 0x2069) ||
                               cp == 0x200e || cp == 0x200f || cp == 0x061c;
        if (invisible) {
            out += "\\u";
            for (int shift = 12; shift >= 0; shift -= 4) out += hex[(cp >> shift) & 15];
        } else {
            out.append(s.substr(i, len));
        }
        i += len;
    }
    return out;
}

std::size_t utf8_decode(std::string_view s, std::size_t i, char32_t& cp) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char b0 = byte(i);
    if (b0 < 0x80) {
        cp = b0;
        return 1;
    }
    // Unicode Table 3-7: the allowed range of the second byte depends on the first.
    std::size_t len = 0;
    unsigned char lo = 0x80, hi = 0xBF;
    if (b0 >= 0xC2 && b0 <= 0xDF) {
        len = 2;
    } else if (b0 >= 0xE0 && b0 <= 0xEF) {
        len = 3;
        if (b0 == 0xE0) lo = 0xA0;  // no overlong forms
        if (b0 == 0xED) hi = 0x9F;  // no surrogates
    } else if (b0 >= 0xF0 && b0 <= 0xF4) {
        len = 4;
        if (b0 == 0xF0) lo = 0x90;  // no overlong forms
        if (b0 == 0xF4) hi = 0x8F;  // nothing above U+10FFFF
    } else {
        return 0;
    }
    if (i + len > s.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
    char32_t value = b0 & (len == 2 ? 0x1Fu : len == 3 ? 0x0Fu : 0x07u);
    for (std::size_t k = 1; k < len; ++k) {
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
        value = (value << 6) | (byte(i + k) & 0x3Fu);
    }
    cp = value;
    return len;
}

void utf8_append(std::string& out, char32_t cp) {
    if (cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) cp = 0xFFFD;
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

void append_u_escape(std::string& out, unsigned char byte) {
    static const char* const digits = "0123456789ABCDEF";
    out += "\\u00";
    out += digits[byte >> 4];
    out += digits[byte & 0xF];
}

std::string code_point_name(char32_t cp) {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "U+%04lX", static_cast<unsigned long>(cp));
    return buffer;
}

bool is_language_tag(std::string_view tag) {
    if (tag.size() > 255) return false;
    const auto alpha = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
    const auto digit = [](char c) { return c >= '0' && c <= '9'; };
    std::size_t start = 0;
    for (bool first = true;; first = false) {
        const std::size_t end = std::min(tag.find('-', start), tag.size());
        const std::size_t len = end - start;
        if (len < 1 || len > 8) return false;
        for (std::size_t i = start; i < end; ++i)
            if (!alpha(tag[i]) && (first || !digit(tag[i]))) return false;
        if (end == tag.size()) return true;
        start = end + 1;
    }
}

std::size_t find_dot_segment(std::string_view iri) {
    constexpr std::size_t npos = std::string_view::npos;
    const std::size_t colon = iri.find(':');
    std::size_t i = colon == npos ? 0 : colon + 1;
    const std::size_t end = std::min({iri.find('?', i), iri.find('#', i), iri.size()});
    if (iri.substr(i, 2) == "//") {  // the authority is no path
        i = iri.find('/', i + 2);
        if (i == npos || i >= end) return npos;
    }
    while (i <= end) {
        const std::size_t slash = std::min(iri.find('/', i), end);
        const std::string_view segment = iri.substr(i, slash - i);
        if (segment == "." || segment == "..") return i;
        i = slash + 1;
    }
    return npos;
}

bool is_calendar_date(std::string_view s) {
    if (s.size() != 10 || s[4] != '-' || s[7] != '-') return false;
    int digits[10] = {};
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (i == 4 || i == 7) continue;
        if (s[i] < '0' || s[i] > '9') return false;
        digits[i] = s[i] - '0';
    }
    const int year = digits[0] * 1000 + digits[1] * 100 + digits[2] * 10 + digits[3];
    const int month = digits[5] * 10 + digits[6];
    const int day = digits[8] * 10 + digits[9];
    if (year == 0 || month < 1 || month > 12 || day < 1) return false;
    const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    const int days[] = {31, leap ? 29 : 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return day <= days[month - 1];
}

namespace {

// The number written by the two ASCII digits at s[i], or -1.
int two_digits(std::string_view s, std::size_t i) {
    if (i + 2 > s.size() || s[i] < '0' || s[i] > '9' || s[i + 1] < '0' || s[i + 1] > '9') return -1;
    return (s[i] - '0') * 10 + (s[i + 1] - '0');
}

}  // namespace

bool is_date_time(std::string_view s) {
    // YYYY-MM-DDThh:mm:ss: 19 characters, then a fraction and a zone.
    if (s.size() < 19 || !is_calendar_date(s.substr(0, 10)) || s[10] != 'T' || s[13] != ':' ||
        s[16] != ':')
        return false;
    const int hour = two_digits(s, 11), minute = two_digits(s, 14), second = two_digits(s, 17);
    if (hour < 0 || hour > 23 || minute < 0 || minute > 59 || second < 0 || second > 59)
        return false;
    std::size_t i = 19;
    if (i < s.size() && s[i] == '.') {
        const std::size_t first = ++i;
        while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
        if (i == first) return false;
    }
    const std::string_view zone = s.substr(i);
    if (zone.empty() || zone == "Z") return true;
    if (zone.size() != 6 || (zone[0] != '+' && zone[0] != '-') || zone[3] != ':') return false;
    const int zone_hours = two_digits(zone, 1), zone_minutes = two_digits(zone, 4);
    if (zone_hours < 0 || zone_minutes < 0 || zone_minutes > 59) return false;
    return zone_hours < 14 || (zone_hours == 14 && zone_minutes == 0);
}

}  // namespace geotex::detail
