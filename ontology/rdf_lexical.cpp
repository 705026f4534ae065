// Lexical forms and checks of the RDF writer, and the public IRI and face-range helpers of
// rdf_writer.hpp.
#include "ontology/rdf_lexical.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "common/detail/text.hpp"
#include "common/errors.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex {
namespace rdf_detail {

using detail::code_point_name;
using detail::is_language_tag;

// ---- text checks ------------------------------------------------------------------------------

std::string hex2(unsigned v) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "%02X", v & 0xFFu);
    return buf;
}

/// A user string that goes into a literal: valid UTF-8 without the characters that one of the
/// three syntaxes cannot carry (XML 1.0 has no NUL and no C0 control but tab, line feed and
/// carriage return; Raptor's XML writer also refuses DEL and the non-characters U+FFFE,
/// U+FFFF). Everything else, quotes, '>', backslashes and newlines included, is escaped by
/// the serialiser.
void check_text(std::string_view s, const std::string& what) {
    for (std::size_t i = 0; i < s.size();) {
        char32_t cp = 0;
        const std::size_t len = detail::utf8_decode(s, i, cp);
        if (len == 0)
            throw InvalidInput("RDF writer: " + what + " is not valid UTF-8 at byte " +
                               std::to_string(i + 1) + " (byte 0x" +
                               hex2(static_cast<unsigned char>(s[i])) + ")");
        const bool control = (cp < 0x20 && cp != '\t' && cp != '\n' && cp != '\r') || cp == 0x7F;
        if (control || cp == 0xFFFE || cp == 0xFFFF)
            throw InvalidInput("RDF writer: " + what + " contains " + code_point_name(cp) +
                               " at byte " + std::to_string(i + 1) +
                               ", which RDF/XML cannot carry; remove it");
        i += len;
    }
}

bool is_ascii_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
bool is_ascii_digit(char c) { return c >= '0' && c <= '9'; }

/// xsd:dateTime lexical form: -?YYYY-MM-DDThh:mm:ss(.s+)?(Z|(+|-)hh:mm)?
bool is_date_time(const std::string& t) {
    std::size_t i = t.size() > 0 && t[0] == '-' ? 1 : 0;
    const auto digits = [&](std::size_t n) {
        for (std::size_t k = 0; k < n; ++k, ++i)
            if (i >= t.size() || !is_ascii_digit(t[i])) return false;
        return true;
    };
    const auto literal = [&](char c) { return i < t.size() && t[i++] == c; };
    std::size_t year = 0;
    while (i + year < t.size() && is_ascii_digit(t[i + year])) ++year;
    if (year < 4) return false;
    i += year;
    if (!(literal('-') && digits(2) && literal('-') && digits(2) && literal('T') && digits(2) &&
          literal(':') && digits(2) && literal(':') && digits(2)))
        return false;
    if (i < t.size() && t[i] == '.') {
        ++i;
        if (!digits(1)) return false;
        while (i < t.size() && is_ascii_digit(t[i])) ++i;
    }
    if (i == t.size()) return true;
    if (t[i] == 'Z') return i + 1 == t.size();
    if (t[i] != '+' && t[i] != '-') return false;
    ++i;
    return digits(2) && literal(':') && digits(2) && i == t.size();
}

void check_language(const std::string& tag, const std::string& what) {
    if (!is_language_tag(tag))
        throw InvalidInput("RDF writer: " + what + ": '" + tag +
                           "' is not a language tag (letters, then '-'-separated letters and "
                           "digits, e.g. en, fr, pt-BR)");
}

bool is_lower_hex(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
        return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
    });
}

void check_sha256(const std::string& hex, const std::string& what) {
    if (hex.size() != 64 || !is_lower_hex(hex))
        throw InvalidInput("RDF writer: " + what +
                           " is not a SHA-256 digest (64 lower-case hexadecimal digits): '" +
                           hex.substr(0, 80) + "'");
}

/// One path segment of an IRI: everything but RFC 3986 unreserved characters is
/// percent-encoded (UTF-8 bytes included), so an id can never add a segment, a query or a
/// fragment; "." and ".." are encoded too, as IRI resolution would remove them.
std::string iri_segment(std::string_view id) {
    std::string out;
    const bool dots_only = id.find_first_not_of('.') == std::string_view::npos;
    for (const char c : id) {
        const auto u = static_cast<unsigned char>(c);
        const bool unreserved = (u >= 'A' && u <= 'Z') || (u >= 'a' && u <= 'z') ||
                                (u >= '0' && u <= '9') || u == '-' || u == '_' || u == '~' ||
                                (u == '.' && !dots_only);
        if (unreserved)
            out += c;
        else
            out += '%' + hex2(u);
    }
    return out;
}

// ---- numbers ------------------------------------------------------------------------------------

/// Shortest lexical form that reads back to the same double, always with a mantissa dot and an
/// exponent ("1.25E1", "1.0E-1", "-0.0E0"), so that Turtle writes it as a double.
std::string double_lexical(double v, const std::string& what) {
    if (!std::isfinite(v))
        throw InvalidInput("RDF writer: " + what + " is not finite (" + std::to_string(v) + ")");
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
    const std::string s(buf, r.ptr);  // e.g. "1.25e+01", "-0e+00"
    const std::size_t e = s.find('e');
    std::string mantissa = s.substr(0, e);
    if (mantissa.find('.') == std::string::npos) mantissa += ".0";
    return mantissa + "E" + std::to_string(std::stoi(s.substr(e + 1)));
}

std::string unescape_string_body(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '\\' || i + 1 >= text.size()) {
            // The bytes up to the next backslash at once (most texts have none).
            const std::size_t next = text.find('\\', i + 1);
            const std::size_t end = next == std::string_view::npos ? text.size() : next;
            out.append(text.data() + i, end - i);
            i = end - 1;
            continue;
        }
        const char e = text[++i];
        switch (e) {
            case 't':
                out += '\t';
                break;
            case 'b':
                out += '\b';
                break;
            case 'n':
                out += '\n';
                break;
            case 'r':
                out += '\r';
                break;
            case 'f':
                out += '\f';
                break;
            case 'u':
            case 'U': {
                const std::size_t n = e == 'u' ? 4 : 8;
                char32_t cp = 0;
                bool ok = i + n < text.size();  // the digits are text[i + 1 .. i + n]
                for (std::size_t k = 1; ok && k <= n; ++k) {
                    const char h = text[i + k];
                    int v = -1;
                    if (h >= '0' && h <= '9') v = h - '0';
                    if (h >= 'a' && h <= 'f') v = h - 'a' + 10;
                    if (h >= 'A' && h <= 'F') v = h - 'A' + 10;
                    if (v < 0) ok = false;
                    cp = cp * 16 + static_cast<char32_t>(v < 0 ? 0 : v);
                }
                if (ok) {
                    detail::utf8_append(out, cp);
                    i += n;
                } else {
                    out += '\\';
                    out += e;
                }
                break;
            }
            default:
                out += e;  // \" \' \\ and anything unknown: the character itself
        }
    }
    return out;
}

/// Canonical xsd:decimal ("-12.5", "0.001", "5.0": always a dot with digits on both sides, so
/// that Turtle writes it as a decimal) of a YAML number such as "5", ".5", "+1e-3", "2.50".
/// Empty when the text is not a number.
std::string canonical_decimal(std::string_view t) {
    std::size_t i = 0;
    bool negative = false;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) negative = t[i++] == '-';
    std::string digits;
    long point = -1;  // number of digits before the decimal point
    bool any_digit = false;
    for (; i < t.size(); ++i) {
        if (t[i] >= '0' && t[i] <= '9') {
            digits += t[i];
            any_digit = true;
        } else if (t[i] == '.' && point < 0) {
            point = static_cast<long>(digits.size());
        } else {
            break;
        }
    }
    if (!any_digit) return {};
    if (point < 0) point = static_cast<long>(digits.size());
    if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
        ++i;
        bool exp_negative = false;
        if (i < t.size() && (t[i] == '+' || t[i] == '-')) exp_negative = t[i++] == '-';
        long exponent = 0;
        bool exp_digit = false;
        for (; i < t.size() && t[i] >= '0' && t[i] <= '9'; ++i) {
            exponent = std::min(exponent * 10 + (t[i] - '0'), 100000L);
            exp_digit = true;
        }
        if (!exp_digit || exponent > 1000) return {};  // a bound beyond 1e±1000 is no double
        point += exp_negative ? -exponent : exponent;
    }
    if (i != t.size()) return {};
    const long n = static_cast<long>(digits.size());
    std::string integer, fraction;
    if (point <= 0) {
        integer = "0";
        fraction = std::string(static_cast<std::size_t>(-point), '0') + digits;
    } else if (point >= n) {
        integer = digits + std::string(static_cast<std::size_t>(point - n), '0');
    } else {
        integer = digits.substr(0, static_cast<std::size_t>(point));
        fraction = digits.substr(static_cast<std::size_t>(point));
    }
    integer.erase(0, std::min(integer.find_first_not_of('0'), integer.size() - 1));
    while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
    if (fraction.empty()) fraction = "0";
    const bool zero = integer == "0" && fraction == "0";
    return (negative && !zero ? "-" : "") + integer + "." + fraction;
}

/// xsd:decimal of a finite dictionary bound, from the text the curator wrote when there is one
/// (it must denote the same double), else from the shortest exact digits of the double.
std::string bound_decimal(const std::string& text, double value, const std::string& what) {
    if (!std::isfinite(value)) throw InvalidInput("RDF writer: " + what + " is not finite");
    std::string decimal;
    if (text.empty()) {
        char buf[1200];  // the longest fixed form of a double has 1077 characters
        const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed);
        decimal = canonical_decimal(std::string_view(buf, static_cast<std::size_t>(r.ptr - buf)));
    } else {
        decimal = canonical_decimal(text);
        if (decimal.empty())
            throw InvalidInput("RDF writer: " + what + ": '" + text.substr(0, 60) +
                               "' is not a decimal number");
        if (std::strtod(decimal.c_str(), nullptr) != value)
            throw InvalidInput("RDF writer: " + what + ": the text '" + text.substr(0, 60) +
                               "' does not denote the bound's value " +
                               double_lexical(value, what));
    }
    return decimal;
}

}  // namespace rdf_detail

using namespace rdf_detail;

namespace {

// The checks of validate_iri and validate_base_iri; `kind` names the IRI in messages.
std::string checked_iri(std::string_view iri, const std::string& kind, bool base) {
    const auto fail = [&](const std::string& what) {
        throw InvalidInput(kind + " '" + std::string(iri.substr(0, 200)) + "': " + what);
    };
    if (iri.empty())
        fail(base ? "empty; give an absolute IRI ending in '/' or '#'"
                  : "empty; give an absolute IRI");
    // Characters are counted in code points, 1-based, so that the position matches what the
    // user sees.
    std::size_t position = 0, hashes = 0;
    for (std::size_t i = 0; i < iri.size();) {
        ++position;
        char32_t cp = 0;
        const std::size_t len = detail::utf8_decode(iri, i, cp);
        if (len == 0)
            fail("byte 0x" + hex2(static_cast<unsigned char>(iri[i])) + " at position " +
                 std::to_string(position) + " is not valid UTF-8");
        const std::string at = " at position " + std::to_string(position);
        if (cp <= 0x20 || (cp >= 0x7F && cp <= 0x9F) || cp == 0xFFFE || cp == 0xFFFF) {
            fail((cp == 0x20 ? "a space (U+0020)" : "control character " + code_point_name(cp)) +
                 at + " is not allowed in an IRI; percent-encode it (e.g. %20 for a space)");
        }
        static const std::string kForbidden = "<>\"{}|\\^`";
        if (cp < 0x80 && kForbidden.find(static_cast<char>(cp)) != std::string::npos)
            fail("character '" + std::string(1, static_cast<char>(cp)) + "' (" +
                 code_point_name(cp) + ")" + at +
                 " is not allowed in an IRI; percent-encode it (%" + hex2(cp) + ")");
        if (cp == '%') {
            const auto is_hex = [&](std::size_t k) {
                return k < iri.size() && std::isxdigit(static_cast<unsigned char>(iri[k]));
            };
            if (!is_hex(i + 1) || !is_hex(i + 2))
                fail("'%'" + at +
                     " is not followed by two hexadecimal digits; write %25 for a '%'");
        }
        if (cp == '#' && ++hashes > 1)
            fail("a second '#'" + at + "; an IRI has at most one fragment");
        i += len;
    }
    // scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"
    const std::size_t colon = iri.find(':');
    bool scheme_ok = colon != std::string_view::npos && colon > 0 && is_ascii_alpha(iri[0]);
    for (std::size_t i = 1; scheme_ok && i < colon; ++i)
        scheme_ok = is_ascii_alpha(iri[i]) || is_ascii_digit(iri[i]) || iri[i] == '+' ||
                    iri[i] == '-' || iri[i] == '.';
    if (!scheme_ok) fail("not absolute: it must start with a scheme such as 'https:' or 'urn:'");
    if (colon + 1 == iri.size()) fail("nothing after the scheme");
    if (base && iri.back() != '/' && iri.back() != '#')
        fail("must end in '/' or '#' so that geotex can append names such as 'texel/12'");
    const std::size_t dot = detail::find_dot_segment(iri);
    if (dot != std::string_view::npos) {
        std::size_t dot_position = 1;
        for (std::size_t i = 0; i < dot; ++dot_position) {
            char32_t cp = 0;
            i += detail::utf8_decode(iri, i, cp);
        }
        const std::string_view segment = iri.substr(dot, iri[dot + 1] == '.' ? 2 : 1);
        fail("the path segment '" + std::string(segment) + "' at position " +
             std::to_string(dot_position) +
             (base ? " is removed when an RDF reader resolves the IRI, so every IRI made from "
                     "this base would read back as another one; remove it"
                   : " is removed when an RDF reader resolves the IRI, so it would read back "
                     "as another IRI; remove it"));
    }
    return std::string(iri);
}

}  // namespace

std::string validate_base_iri(std::string_view iri) { return checked_iri(iri, "base IRI", true); }

std::string validate_iri(std::string_view iri, const std::string& kind) {
    return checked_iri(iri, kind, false);
}

std::string face_ranges(const std::vector<int>& sorted_faces) {
    std::string out;
    for (std::size_t i = 0; i < sorted_faces.size();) {
        if (sorted_faces[i] < 0)
            throw InvalidInput("face_ranges: negative face index " +
                               std::to_string(sorted_faces[i]));
        std::size_t j = i;
        while (j + 1 < sorted_faces.size() && sorted_faces[j + 1] == sorted_faces[j] + 1) ++j;
        if (j + 1 < sorted_faces.size() && sorted_faces[j + 1] <= sorted_faces[j])
            throw InvalidInput("face_ranges: faces not strictly increasing at position " +
                               std::to_string(j + 1) + " (" + std::to_string(sorted_faces[j]) +
                               " then " + std::to_string(sorted_faces[j + 1]) + ")");
        if (!out.empty()) out += ' ';
        out += std::to_string(sorted_faces[i]);
        if (j > i) out += '-' + std::to_string(sorted_faces[j]);
        i = j + 1;
    }
    return out;
}

}  // namespace geotex
