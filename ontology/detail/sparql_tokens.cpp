#include "ontology/detail/sparql_tokens.hpp"

#include <algorithm>
#include <cstring>

namespace geotex::detail {

namespace {

using Kind = SparqlToken::Kind;

bool is_alpha(unsigned char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
bool is_digit(unsigned char c) { return c >= '0' && c <= '9'; }
/// Characters of a variable name or a prefixed name's parts (UTF-8 bytes count as letters).
bool is_name_char(unsigned char c) { return is_alpha(c) || is_digit(c) || c == '_' || c >= 0x80; }

// ---------------------------------------------------------------------------------------
// Tokens

class Lexer {
  public:
    explicit Lexer(std::string_view text) : s_(text) {}

    std::vector<SparqlToken> run() {
        std::vector<SparqlToken> out;
        while (true) {
            skip_space_and_comments();
            if (i_ >= s_.size()) break;
            SparqlToken t;
            t.begin = i_;
            t.line = line_;
            t.column = static_cast<long>(i_ - line_start_) + 1;
            t.kind = scan();
            t.end = i_;
            out.push_back(t);
        }
        return out;
    }

  private:
    std::string_view s_;
    std::size_t i_ = 0;
    long line_ = 1;
    std::size_t line_start_ = 0;

    char at(std::size_t k) const { return k < s_.size() ? s_[k] : '\0'; }

    void advance() {
        if (s_[i_] == '\n') {
            ++line_;
            line_start_ = i_ + 1;
        }
        ++i_;
    }

    void skip_space_and_comments() {
        while (i_ < s_.size()) {
            const char c = s_[i_];
            if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
                advance();
            } else if (c == '#') {
                while (i_ < s_.size() && s_[i_] != '\n') ++i_;
            } else {
                break;
            }
        }
    }

    Kind scan() {
        const auto c = static_cast<unsigned char>(s_[i_]);
        if (c == '<') return scan_iri_or_less();
        if (c == '"' || c == '\'') return scan_string();
        if ((c == '?' || c == '$') && is_name_char(static_cast<unsigned char>(at(i_ + 1)))) {
            ++i_;
            while (i_ < s_.size() && is_name_char(static_cast<unsigned char>(s_[i_]))) ++i_;
            return Kind::Variable;
        }
        if (c == '_' && at(i_ + 1) == ':') {
            i_ += 2;
            scan_local_part();
            return Kind::BlankLabel;
        }
        if (c == '@' && is_alpha(static_cast<unsigned char>(at(i_ + 1)))) {
            ++i_;
            while (i_ < s_.size() &&
                   (is_alpha(static_cast<unsigned char>(s_[i_])) ||
                    is_digit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '-'))
                ++i_;
            return Kind::LangTag;
        }
        if (is_digit(c) || (c == '.' && is_digit(static_cast<unsigned char>(at(i_ + 1)))))
            return scan_number();
        if (is_alpha(c) || c == ':' || c >= 0x80 || c == '_') return scan_name();
        // Two-character operators, then one character.
        static const char* const pairs[] = {"^^", "&&", "||", "!=", "<=", ">="};
        for (const char* p : pairs) {
            if (c == static_cast<unsigned char>(p[0]) && at(i_ + 1) == p[1]) {
                i_ += 2;
                return Kind::Punct;
            }
        }
        advance();
        return Kind::Punct;
    }

    Kind scan_iri_or_less() {
        // SPARQL's IRIREF: no space, no control character, none of <>"{}|^`\ inside; else
        // the less-than operator.
        std::size_t k = i_ + 1;
        while (k < s_.size()) {
            const auto ch = static_cast<unsigned char>(s_[k]);
            if (ch == '>') {
                i_ = k + 1;
                return Kind::Iri;
            }
            if (ch <= 0x20 || std::strchr("<\"{}|^`\\", ch) != nullptr) break;
            ++k;
        }
        i_ += at(i_ + 1) == '=' ? 2 : 1;
        return Kind::Punct;
    }

    Kind scan_string() {
        const char q = s_[i_];
        const bool triple = at(i_ + 1) == q && at(i_ + 2) == q;
        i_ += triple ? 3 : 1;
        while (i_ < s_.size()) {
            if (s_[i_] == '\\') {
                i_ = std::min(i_ + 2, s_.size());
                continue;
            }
            if (s_[i_] == q && (!triple || (at(i_ + 1) == q && at(i_ + 2) == q))) {
                i_ += triple ? 3 : 1;
                return Kind::String;
            }
            if (!triple && s_[i_] == '\n') return Kind::String;  // Rasqal reports it
            advance();
        }
        return Kind::String;
    }

    Kind scan_number() {
        while (is_digit(static_cast<unsigned char>(at(i_)))) ++i_;
        if (at(i_) == '.' && is_digit(static_cast<unsigned char>(at(i_ + 1)))) {
            ++i_;
            while (is_digit(static_cast<unsigned char>(at(i_)))) ++i_;
        }
        if (at(i_) == 'e' || at(i_) == 'E') {
            std::size_t k = i_ + 1;
            if (at(k) == '+' || at(k) == '-') ++k;
            if (is_digit(static_cast<unsigned char>(at(k)))) {
                i_ = k;
                while (is_digit(static_cast<unsigned char>(at(i_)))) ++i_;
            }
        }
        return Kind::Number;
    }

    /// The local part of a prefixed name or blank node label: name characters, '-', '.'
    /// (not last), ':', %hh and \-escapes.
    void scan_local_part() {
        while (i_ < s_.size()) {
            const auto ch = static_cast<unsigned char>(s_[i_]);
            if (is_name_char(ch) || ch == '-' || ch == ':') {
                ++i_;
            } else if (ch == '%' && i_ + 2 < s_.size()) {
                i_ += 3;
            } else if (ch == '\\' && i_ + 1 < s_.size()) {
                i_ += 2;
            } else if (ch == '.') {
                // A '.' ends the name unless a name character follows.
                std::size_t k = i_;
                while (at(k) == '.') ++k;
                const auto next = static_cast<unsigned char>(at(k));
                if (is_name_char(next) || next == '-' || next == ':' || next == '%' || next == '\\')
                    i_ = k;
                else
                    break;
            } else {
                break;
            }
        }
    }

    Kind scan_name() {
        const std::size_t start = i_;
        // The prefix: up to ':' (names without one are keywords).
        while (i_ < s_.size()) {
            const auto ch = static_cast<unsigned char>(s_[i_]);
            if (is_name_char(ch) || ch == '-') {
                ++i_;
            } else if (ch == '.' && (is_name_char(static_cast<unsigned char>(at(i_ + 1))) ||
                                     at(i_ + 1) == '-')) {
                ++i_;
            } else {
                break;
            }
        }
        if (at(i_) != ':') return i_ > start ? Kind::Word : (advance(), Kind::Punct);
        ++i_;
        scan_local_part();
        return Kind::PrefixedName;
    }
};

}  // namespace

std::vector<SparqlToken> tokenize_sparql(std::string_view query) { return Lexer(query).run(); }

bool is_keyword(std::string_view query, const SparqlToken& t, std::string_view upper) {
    if (t.kind != SparqlToken::Kind::Word) return false;
    const std::string_view x = token_text(query, t);
    if (x.size() != upper.size()) return false;
    for (std::size_t i = 0; i < x.size(); ++i)
        if ((x[i] >= 'a' && x[i] <= 'z' ? x[i] - 32 : x[i]) != upper[i]) return false;
    return true;
}

std::string apply_edits(const std::string& query, std::vector<TextEdit> edits) {
    std::sort(edits.begin(), edits.end(),
              [](const TextEdit& a, const TextEdit& b) { return a.begin < b.begin; });
    std::string out;
    std::size_t at = 0;
    for (const TextEdit& e : edits) {
        out.append(query, at, e.begin - at);
        out += e.text;
        at = e.end;
    }
    out.append(query, at, std::string::npos);
    return out;
}

std::string line_breaks(std::string_view query, std::size_t begin, std::size_t end) {
    return std::string(
        static_cast<std::size_t>(std::count(query.begin() + static_cast<long>(begin),
                                            query.begin() + static_cast<long>(end), '\n')),
        '\n');
}

}  // namespace geotex::detail
