#include "annotation/detail/dictionary_text.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "common/detail/text.hpp"

namespace geotex::dictionary_detail {

/// Optimal string alignment distance (Levenshtein plus transpositions, so that the common
/// typo "lables" is one edit from "labels").
size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

/// The candidate closest to `word`, when close enough to be a plausible typo ("" otherwise).
/// `candidates` pairs a spelling to compare with and the name to suggest for it.
std::string closest(const std::string& word,
                    const std::vector<std::pair<std::string, std::string>>& candidates) {
    std::string lower = word;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::string best;
    size_t best_distance = std::string::npos;
    for (const auto& [spelling, name] : candidates) {
        const size_t d = edit_distance(lower, spelling);
        if (d < best_distance) best_distance = d, best = name;
    }
    const size_t shorter = std::min(lower.size(), best.size());
    const size_t allowed = shorter <= 3 ? 1 : std::max<size_t>(2, shorter / 3);
    return best_distance <= allowed ? best : std::string();
}

std::string join(const std::vector<std::string>& words, const char* separator) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : separator) + w;
    return out;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

bool is_id(const std::string& s) {
    if (s.empty() || !std::isalnum(static_cast<unsigned char>(s[0]))) return false;
    return std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
    });
}

/// First character of `s` that has no place in a text of the dictionary, or -1: a tab or a
/// line break in a one-line text (labels, titles, ids), a carriage return anywhere (Turtle
/// writers pass it through raw), and, in a double-quoted scalar (`escaped`), any control
/// character its escapes produced. Raw control characters elsewhere are reported for the
/// whole text by check_encoding.
long forbidden_control(const std::string& s, bool multi_line, bool escaped) {
    for (size_t i = 0; i < s.size();) {
        char32_t cp = 0;
        const size_t n = detail::utf8_decode(s, i, cp);
        if (n == 0) {  // ill-formed UTF-8 is reported for the whole text, not here
            ++i;
            continue;
        }
        if (cp == '\r' || ((cp == '\n' || cp == '\t') && !multi_line)) return static_cast<long>(cp);
        const bool control = cp < 0x20 || (cp >= 0x7F && cp < 0xA0);
        if (control && escaped && cp != '\n' && cp != '\t') return static_cast<long>(cp);
        i += n;
    }
    return -1;
}

namespace {

/// An absolute IRI as RDF needs it (the rules of validate_base_iri and validate_iri, which
/// the RDF writer applies): scheme ":" rest, no space, no character that IRIs forbid, '%'
/// only before two hexadecimal digits, at most one '#', no "." or ".." path segment (readers
/// resolve those away); a namespace (`as_namespace`) also ends in '/' or '#' so that concept
/// ids can be appended. Returns the reason when not, "" when fine.
std::string absolute_iri_problem(const std::string& iri, bool as_namespace) {
    const size_t colon = iri.find(':');
    if (iri.empty() || colon == std::string::npos || colon == 0 ||
        !std::isalpha(static_cast<unsigned char>(iri[0])))
        return as_namespace
                   ? "is not an absolute IRI (it needs a scheme, e.g. https://example.org/dict#)"
                   : "is not an absolute IRI (it needs a scheme, e.g. https://example.org/x)";
    for (size_t i = 0; i < colon; ++i) {
        const char c = iri[i];
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.'))
            return "is not an absolute IRI (bad scheme before ':')";
    }
    for (size_t i = 0; i < iri.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(iri[i]);
        if (c <= 0x20 || c == 0x7F ||
            std::string_view("<>\"{}|\\^`").find(static_cast<char>(c)) != std::string_view::npos)
            return "contains a character that IRIs forbid at position " + std::to_string(i + 1) +
                   " (percent-encode it)";
        if (c == '%' &&
            (i + 2 >= iri.size() || !std::isxdigit(static_cast<unsigned char>(iri[i + 1])) ||
             !std::isxdigit(static_cast<unsigned char>(iri[i + 2]))))
            return "has a '%' at position " + std::to_string(i + 1) +
                   " that is not followed by two hexadecimal digits (write %25 for a '%')";
    }
    if (std::count(iri.begin(), iri.end(), '#') > 1)
        return "has more than one '#' (an IRI has at most one fragment)";
    if (as_namespace && iri.back() != '/' && iri.back() != '#')
        return "must end in '/' or '#' (concept IRIs are the namespace followed by the concept id)";
    const size_t dot = detail::find_dot_segment(iri);
    if (dot != std::string::npos)
        return "has a '" + iri.substr(dot, iri[dot + 1] == '.' ? 2 : 1) +
               "' path segment at position " + std::to_string(dot + 1) +
               ", which RDF readers resolve away (" +
               (as_namespace ? "the concept IRIs would read back as others"
                             : "it would read back as another IRI") +
               "); remove it";
    return "";
}

}  // namespace

std::string namespace_problem(const std::string& iri) { return absolute_iri_problem(iri, true); }

std::string iri_problem(const std::string& iri) { return absolute_iri_problem(iri, false); }

/// Rewrites a YAML decimal or scientific number as an xsd:decimal lexical form without
/// exponent, trailing zeros or a '+' sign ("1.50e-2" -> "0.015", "-0" -> "0"). Works on the
/// digits, so the text is exactly the number written. Returns false when `s` is not a number
/// in that syntax or its exponent is absurdly large.
bool decimal_text(const std::string& s, std::string& out) {
    size_t i = 0;
    bool negative = false;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) negative = s[i++] == '-';
    std::string digits;
    long point = 0;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) digits += s[i++];
    point = static_cast<long>(digits.size());
    if (i < s.size() && s[i] == '.') {
        ++i;
        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) digits += s[i++];
    }
    if (digits.empty()) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        bool exp_negative = false;
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) exp_negative = s[i++] == '-';
        long exponent = 0;
        const size_t first = i;
        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) {
            exponent = exponent * 10 + (s[i++] - '0');
            if (exponent > 1000) return false;
        }
        if (i == first) return false;
        point += exp_negative ? -exponent : exponent;
    }
    if (i != s.size()) return false;
    while (!digits.empty() && digits.front() == '0') digits.erase(0, 1), --point;
    while (!digits.empty() && digits.back() == '0') digits.pop_back();
    if (digits.empty()) {
        out = "0";
        return true;
    }
    const long n = static_cast<long>(digits.size());
    if (point <= 0)
        out = "0." + std::string(static_cast<size_t>(-point), '0') + digits;
    else if (point >= n)
        out = digits + std::string(static_cast<size_t>(point - n), '0');
    else
        out = digits.substr(0, static_cast<size_t>(point)) + "." +
              digits.substr(static_cast<size_t>(point));
    if (negative) out = "-" + out;
    return true;
}

}  // namespace geotex::dictionary_detail
