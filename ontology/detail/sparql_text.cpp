#include "ontology/detail/sparql_text.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <utility>

#include "geometry/detail/text.hpp"
#include "geometry/errors.hpp"

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
            while (i_ < s_.size() && (is_alpha(static_cast<unsigned char>(s_[i_])) ||
                                      is_digit(static_cast<unsigned char>(s_[i_])) ||
                                      s_[i_] == '-'))
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
                if (is_name_char(next) || next == '-' || next == ':' || next == '%' ||
                    next == '\\')
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

// ---------------------------------------------------------------------------------------
// Property paths

struct Path {
    enum class Op { Link, Inverse, Sequence, Alternative, Negated };
    Op op = Op::Link;
    std::string link;                           // Link: the IRI or prefixed name as written
    std::vector<std::unique_ptr<Path>> parts;   // Inverse: 1; Sequence, Alternative: 2 or more
    std::vector<std::pair<bool, std::string>> negated;  // Negated: (inverse?, IRI)
};

/// Thrown where the rewriter cannot read the query; the query then goes to Rasqal unchanged.
struct Malformed {};

const char* const kRdfType = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>";

/// A text replacement in the query.
struct Edit {
    std::size_t begin, end;
    std::string text;
};

class PathRewriter {
  public:
    PathRewriter(const std::string& query, std::vector<SparqlToken> tokens, std::string prefix)
        : q_(query), t_(std::move(tokens)), prefix_(std::move(prefix)) {}

    std::vector<Edit> run() {
        while (k_ < t_.size()) {
            if (is_word("VALUES")) {
                while (!at_end() && !is_punct("{")) ++k_;
                if (!at_end()) skip_balanced();
            } else if (is_punct("{")) {
                group();
            } else {
                ++k_;
            }
        }
        return std::move(edits_);
    }

  private:
    const std::string& q_;
    std::vector<SparqlToken> t_;
    std::string prefix_;
    std::size_t k_ = 0;
    int fresh_ = 0;
    std::vector<Edit> edits_;

    std::string_view text(const SparqlToken& t) const {
        return std::string_view(q_).substr(t.begin, t.end - t.begin);
    }
    bool at_end() const { return k_ >= t_.size(); }
    bool is_punct(std::string_view p, std::size_t k) const {
        return k < t_.size() && t_[k].kind == Kind::Punct && text(t_[k]) == p;
    }
    bool is_punct(std::string_view p) const { return is_punct(p, k_); }
    bool is_word(std::string_view w, std::size_t k) const {
        if (k >= t_.size() || t_[k].kind != Kind::Word) return false;
        const std::string_view x = text(t_[k]);
        auto upper = [](char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 32) : c; };
        return x.size() == w.size() && std::equal(x.begin(), x.end(), w.begin(),
                                                  [&](char a, char b) { return upper(a) == upper(b); });
    }
    bool is_word(std::string_view w) const { return is_word(w, k_); }

    [[noreturn]] void fail(const std::string& what, std::size_t k) const {
        const SparqlToken& t = k < t_.size() ? t_[k] : t_.back();
        throw InvalidInput(what, "", t.line, t.column);
    }
    /// Not SPARQL as far as the rewriter reads it: Rasqal will say what is wrong.
    [[noreturn]] static void malformed() { throw Malformed{}; }

    /// Skips a bracketed run starting at the current opening bracket.
    void skip_balanced() {
        int depth = 0;
        while (!at_end()) {
            const std::string_view x = t_[k_].kind == Kind::Punct ? text(t_[k_]) : "";
            if (x == "(" || x == "{" || x == "[") ++depth;
            if (x == ")" || x == "}" || x == "]") --depth;
            ++k_;
            if (depth <= 0) return;
        }
    }

    // GroupGraphPattern: '{' ... '}', elements until the closing brace.
    void group() {
        ++k_;  // '{'
        while (!at_end() && !is_punct("}")) {
            if (is_punct("{")) {
                group();
            } else if (is_word("SELECT")) {
                // A subquery: its own WHERE clause, then its modifiers up to our '}'.
                while (!at_end() && !is_punct("{") && !is_punct("}")) ++k_;
                if (is_punct("{")) group();
                while (!at_end() && !is_punct("}")) {
                    if (is_punct("{"))
                        skip_balanced();  // a trailing VALUES block
                    else
                        ++k_;
                }
            } else if (is_word("OPTIONAL") || is_word("MINUS") || is_word("UNION")) {
                ++k_;
            } else if (is_word("GRAPH") || is_word("SERVICE")) {
                while (!at_end() && !is_punct("{") && !is_punct("}")) ++k_;
            } else if (is_word("FILTER")) {
                ++k_;
                filter_constraint();
            } else if (is_word("BIND")) {
                ++k_;
                if (is_punct("(")) skip_balanced();
            } else if (is_word("VALUES")) {
                while (!at_end() && !is_punct("{") && !is_punct("}")) ++k_;
                if (is_punct("{")) skip_balanced();
            } else if (is_punct(".")) {
                ++k_;
            } else {
                statement();
            }
        }
        if (!at_end()) ++k_;  // '}'
    }

    void filter_constraint() {
        if (is_word("NOT")) ++k_;
        if (is_word("EXISTS")) {
            ++k_;
            if (is_punct("{")) group();
            return;
        }
        if (!at_end() && t_[k_].kind != Kind::Punct) ++k_;  // a function or built-in name
        if (is_punct("(")) skip_balanced();
    }

    // A node of a triple pattern: [first, last] tokens; `complex` for [ ... ] and ( ... ).
    struct Node {
        std::size_t first = 0, last = 0;
        bool complex = false;
    };

    Node node() {
        Node n;
        n.first = k_;
        if (at_end()) malformed();
        if (is_punct("[")) {
            ++k_;
            if (!is_punct("]")) property_list(true);
            if (!is_punct("]")) malformed();
            n.complex = k_ != n.first + 1;
        } else if (is_punct("(")) {
            ++k_;
            while (!at_end() && !is_punct(")")) node();
            n.complex = k_ != n.first + 1;
        } else if (is_punct("+") || is_punct("-")) {
            ++k_;  // the sign of a number
        } else if (t_[k_].kind == Kind::String) {
            if (k_ + 1 < t_.size() && t_[k_ + 1].kind == Kind::LangTag) {
                ++k_;
            } else if (is_punct("^^", k_ + 1)) {
                k_ += 2;
            }
        }
        n.last = k_;
        if (!at_end()) ++k_;
        return n;
    }

    std::string node_text(const Node& n) const {
        return q_.substr(t_[n.first].begin, t_[n.last].end - t_[n.first].begin);
    }

    bool starts_path_primary() const {
        if (at_end()) return false;
        const SparqlToken& t = t_[k_];
        return t.kind == Kind::Iri || t.kind == Kind::PrefixedName || is_word("A") ||
               is_punct("(") || is_punct("!");
    }

    std::string link_text() {
        std::string x = is_word("A") ? kRdfType : std::string(text(t_[k_]));
        ++k_;
        return x;
    }

    std::unique_ptr<Path> path_alternative() {
        auto first = path_sequence();
        if (!is_punct("|")) return first;
        auto alt = std::make_unique<Path>();
        alt->op = Path::Op::Alternative;
        alt->parts.push_back(std::move(first));
        while (is_punct("|")) {
            ++k_;
            alt->parts.push_back(path_sequence());
        }
        return alt;
    }

    std::unique_ptr<Path> path_sequence() {
        auto first = path_inverse();
        if (!is_punct("/")) return first;
        auto seq = std::make_unique<Path>();
        seq->op = Path::Op::Sequence;
        seq->parts.push_back(std::move(first));
        while (is_punct("/")) {
            ++k_;
            seq->parts.push_back(path_inverse());
        }
        return seq;
    }

    std::unique_ptr<Path> path_inverse() {
        if (!is_punct("^")) return path_element();
        ++k_;
        auto inv = std::make_unique<Path>();
        inv->op = Path::Op::Inverse;
        inv->parts.push_back(path_element());
        return inv;
    }

    std::unique_ptr<Path> path_element() {
        const std::size_t start = k_;
        std::unique_ptr<Path> p;
        if (is_punct("(")) {
            ++k_;
            p = path_alternative();
            if (!is_punct(")")) malformed();
            ++k_;
        } else if (is_punct("!")) {
            ++k_;
            p = std::make_unique<Path>();
            p->op = Path::Op::Negated;
            if (is_punct("(")) {
                ++k_;
                while (!at_end() && !is_punct(")")) {
                    negated_member(*p);
                    if (is_punct("|")) ++k_;
                }
                if (!is_punct(")")) malformed();
                ++k_;
            } else {
                negated_member(*p);
            }
        } else if (starts_path_primary()) {
            p = std::make_unique<Path>();
            p->link = link_text();
        } else {
            malformed();
        }
        if (is_punct("?") || is_punct("*") || is_punct("+")) {
            const std::string_view mod = text(t_[k_]);
            const char* name = mod == "?"   ? "zero or one"
                               : mod == "*" ? "zero or more"
                                            : "one or more";
            fail("the property path " + q_.substr(t_[start].begin, t_[k_].end - t_[start].begin) +
                     " (" + name +
                     ") is not supported: Rasqal 0.9.33 has no property paths, and geotex query "
                     "rewrites only those that are a fixed set of triple patterns (p/q, ^p, p|q, "
                     "!p, grouping); run the query in a triple store",
                 start);
        }
        return p;
    }

    void negated_member(Path& p) {
        bool inverse = false;
        if (is_punct("^")) {
            inverse = true;
            ++k_;
        }
        if (at_end() || !(t_[k_].kind == Kind::Iri || t_[k_].kind == Kind::PrefixedName ||
                          is_word("A")))
            malformed();
        p.negated.emplace_back(inverse, link_text());
    }

    /// One verb of a property list: a variable, or a path (a single link is a plain
    /// property). `simple` is its text when no rewriting is needed.
    struct Verb {
        std::unique_ptr<Path> path;
        std::string simple;
        std::size_t first = 0;
    };

    Verb verb() {
        Verb v;
        v.first = k_;
        if (!at_end() && t_[k_].kind == Kind::Variable) {
            v.simple = std::string(text(t_[k_]));
            ++k_;
            return v;
        }
        v.path = path_alternative();
        if (v.path->op == Path::Op::Link) {
            v.simple = v.path->link;
            v.path.reset();
        }
        return v;
    }

    struct Predicate {
        Verb verb;
        std::vector<Node> objects;
    };

    /// PropertyListPathNotEmpty; inside [ ... ] a path is refused (its node has no name to
    /// repeat in the rewritten patterns).
    std::vector<Predicate> property_list(bool in_brackets) {
        std::vector<Predicate> list;
        while (!at_end()) {
            Predicate pr;
            pr.verb = verb();
            if (pr.verb.path && in_brackets)
                fail("a property path inside [ ... ] is not supported by geotex query: name "
                     "the node with a variable",
                     pr.verb.first);
            pr.objects.push_back(node());
            while (is_punct(",")) {
                ++k_;
                pr.objects.push_back(node());
            }
            list.push_back(std::move(pr));
            if (!is_punct(";")) break;
            while (is_punct(";")) ++k_;
            if (at_end() || is_punct(".") || is_punct("}") || is_punct("]")) break;
        }
        return list;
    }

    void statement() {
        const Node subject = node();
        if (is_punct(".") || is_punct("}")) return;  // [ ... ] alone, or ( ... ) alone
        std::vector<Predicate> list = property_list(false);
        const bool has_path = std::any_of(list.begin(), list.end(),
                                          [](const Predicate& p) { return p.verb.path != nullptr; });
        if (!has_path) return;
        if (subject.complex)
            fail("a property path in a pattern whose subject is [ ... ] or ( ... ) is not "
                 "supported by geotex query: name the node with a variable",
                 subject.first);
        const std::string s = node_text(subject);
        std::vector<std::string> pieces;
        for (const Predicate& pr : list) {
            for (const Node& o : pr.objects) {
                if (!pr.verb.path) {
                    pieces.push_back(s + " " + pr.verb.simple + " " + node_text(o));
                    continue;
                }
                if (o.complex)
                    fail("a property path to an object [ ... ] or ( ... ) is not supported by "
                         "geotex query: name the node with a variable",
                         o.first);
                expand(*pr.verb.path, s, node_text(o), pieces);
            }
        }
        const Node& last = list.back().objects.back();
        const std::size_t begin = t_[subject.first].begin;
        const std::size_t end = t_[last.last].end;
        std::string replacement;
        for (std::size_t i = 0; i < pieces.size(); ++i) {
            if (i > 0) replacement += " . ";
            replacement += pieces[i];
        }
        // The same line breaks, so that later lines keep their numbers in Rasqal's messages.
        replacement.append(
            static_cast<std::size_t>(std::count(q_.begin() + static_cast<long>(begin),
                                                q_.begin() + static_cast<long>(end), '\n')),
            '\n');
        edits_.push_back({begin, end, std::move(replacement)});
    }

    std::string fresh_variable() { return "?" + prefix_ + std::to_string(++fresh_); }

    void expand(const Path& p, const std::string& s, const std::string& o,
                std::vector<std::string>& out) {
        switch (p.op) {
            case Path::Op::Link:
                out.push_back(s + " " + p.link + " " + o);
                break;
            case Path::Op::Inverse:
                expand(*p.parts[0], o, s, out);
                break;
            case Path::Op::Sequence: {
                std::string from = s;
                for (std::size_t i = 0; i < p.parts.size(); ++i) {
                    const std::string to = i + 1 == p.parts.size() ? o : fresh_variable();
                    expand(*p.parts[i], from, to, out);
                    from = to;
                }
                break;
            }
            case Path::Op::Alternative: {
                std::string u;
                for (std::size_t i = 0; i < p.parts.size(); ++i) {
                    std::vector<std::string> branch;
                    expand(*p.parts[i], s, o, branch);
                    if (i > 0) u += " UNION ";
                    u += "{ " + join(branch) + " }";
                }
                out.push_back(std::move(u));
                break;
            }
            case Path::Op::Negated: {
                // SPARQL: the forward members are excluded from s ?p o, the inverse ones
                // from o ?p s; with members of both kinds, the union of the two.
                std::vector<std::string> forward, inverse;
                for (const auto& [is_inverse, iri] : p.negated)
                    (is_inverse ? inverse : forward).push_back(iri);
                std::string g;
                if (!forward.empty() || inverse.empty()) g = negated_group(s, o, forward);
                if (!inverse.empty()) {
                    if (!g.empty()) g += " UNION ";
                    g += negated_group(o, s, inverse);
                }
                out.push_back(std::move(g));
                break;
            }
        }
    }

    std::string negated_group(const std::string& s, const std::string& o,
                              const std::vector<std::string>& excluded) {
        const std::string v = fresh_variable();
        std::string g = "{ " + s + " " + v + " " + o;
        for (std::size_t i = 0; i < excluded.size(); ++i)
            g += (i ? " && " : " FILTER(") + v + " != " + excluded[i];
        if (!excluded.empty()) g += ")";
        return g + " }";
    }

    static std::string join(const std::vector<std::string>& pieces) {
        std::string x;
        for (std::size_t i = 0; i < pieces.size(); ++i) x += (i ? " . " : "") + pieces[i];
        return x;
    }
};

}  // namespace

std::vector<SparqlToken> tokenize_sparql(std::string_view query) { return Lexer(query).run(); }

std::string rewrite_property_paths(const std::string& query, std::string* fresh_prefix) {
    std::vector<SparqlToken> tokens = tokenize_sparql(query);
    // A prefix that no variable of the query starts with.
    std::string prefix = "_path";
    auto used = [&](const std::string& p) {
        return std::any_of(tokens.begin(), tokens.end(), [&](const SparqlToken& t) {
            return t.kind == Kind::Variable &&
                   query.compare(t.begin + 1, p.size(), p) == 0;
        });
    };
    while (used(prefix)) prefix += "_";
    if (fresh_prefix) *fresh_prefix = prefix;

    std::vector<Edit> edits;
    try {
        edits = PathRewriter(query, std::move(tokens), prefix).run();
    } catch (const Malformed&) {
        return query;
    }
    if (edits.empty()) return query;
    std::string out;
    std::size_t at = 0;
    for (const Edit& e : edits) {
        out.append(query, at, e.begin - at);
        out += e.text;
        at = e.end;
    }
    out.append(query, at, std::string::npos);
    return out;
}

std::string remove_order_by(const std::string& query) {
    const std::vector<SparqlToken> tokens = tokenize_sparql(query);
    auto is_word = [&](std::size_t k, std::string_view w) {
        if (k >= tokens.size() || tokens[k].kind != Kind::Word) return false;
        std::string upper = query.substr(tokens[k].begin, tokens[k].end - tokens[k].begin);
        for (char& c : upper) c = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c;
        return upper == w;
    };
    int depth = 0;
    for (std::size_t k = 0; k < tokens.size(); ++k) {
        const std::string_view x =
            std::string_view(query).substr(tokens[k].begin, tokens[k].end - tokens[k].begin);
        if (tokens[k].kind == Kind::Punct && (x == "{" || x == "(")) ++depth;
        if (tokens[k].kind == Kind::Punct && (x == "}" || x == ")")) --depth;
        if (depth != 0 || !is_word(k, "ORDER") || !is_word(k + 1, "BY")) continue;
        // The clause runs to LIMIT, OFFSET, VALUES or the end.
        std::size_t last = k + 1;
        int inner = 0;
        for (std::size_t j = k + 2; j < tokens.size(); ++j) {
            const std::string_view y =
                std::string_view(query).substr(tokens[j].begin, tokens[j].end - tokens[j].begin);
            if (inner == 0 && (is_word(j, "LIMIT") || is_word(j, "OFFSET") || is_word(j, "VALUES")))
                break;
            if (tokens[j].kind == Kind::Punct && (y == "(" || y == "{")) ++inner;
            if (tokens[j].kind == Kind::Punct && (y == ")" || y == "}")) --inner;
            last = j;
        }
        const std::size_t begin = tokens[k].begin, end = tokens[last].end;
        std::string out = query.substr(0, begin);
        out.append(static_cast<std::size_t>(std::count(query.begin() + static_cast<long>(begin),
                                                       query.begin() + static_cast<long>(end), '\n')),
                   '\n');
        out += query.substr(end);
        return out;
    }
    return query;
}

std::string where_clause_as_ask(const std::string& query) {
    const std::vector<SparqlToken> tokens = tokenize_sparql(query);
    auto text = [&](std::size_t k) {
        return std::string_view(query).substr(tokens[k].begin, tokens[k].end - tokens[k].begin);
    };
    auto word_is = [&](std::size_t k, std::string_view w) {
        if (tokens[k].kind != Kind::Word) return false;
        std::string upper(text(k));
        for (char& c : upper) c = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c;
        return upper == w;
    };
    std::size_t k = 0;
    while (k < tokens.size() && !word_is(k, "SELECT")) {
        if (word_is(k, "ASK") || word_is(k, "CONSTRUCT") || word_is(k, "DESCRIBE")) return {};
        ++k;
    }
    const std::size_t select = k;
    while (k < tokens.size() && !(tokens[k].kind == Kind::Punct && text(k) == "{")) ++k;
    if (k >= tokens.size()) return {};
    const std::size_t open = k;
    int depth = 0;
    for (; k < tokens.size(); ++k) {
        if (tokens[k].kind != Kind::Punct) continue;
        if (text(k) == "{") ++depth;
        if (text(k) == "}" && --depth == 0) break;
    }
    if (k >= tokens.size()) return {};
    const std::size_t close = k;
    std::string ask = query.substr(0, select < tokens.size() ? tokens[select].begin : 0);
    ask += "ASK ";
    ask += query.substr(tokens[open].begin, tokens[close].end - tokens[open].begin);
    for (k = close + 1; k < tokens.size(); ++k) {
        if (word_is(k, "VALUES")) {
            ask += "\n";
            ask += query.substr(tokens[k].begin);
            break;
        }
    }
    return ask;
}

namespace {

/// The text of a SPARQL string token (quotes removed, escapes resolved).
std::string unescape_string(std::string_view token) {
    const bool triple = token.size() >= 6 && token[1] == token[0] && token[2] == token[0];
    const std::size_t quote = triple ? 3 : 1;
    if (token.size() < 2 * quote) return {};
    const std::string_view body = token.substr(quote, token.size() - 2 * quote);
    std::string out;
    for (std::size_t i = 0; i < body.size(); ++i) {
        if (body[i] != '\\' || i + 1 >= body.size()) {
            out += body[i];
            continue;
        }
        const char e = body[++i];
        switch (e) {
            case 't': out += '\t'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'u':
            case 'U': {
                const std::size_t n = e == 'u' ? 4 : 8;
                const std::string digits(body.substr(i + 1, n));
                if (digits.size() == n &&
                    digits.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos) {
                    geotex::detail::utf8_append(out, static_cast<char32_t>(std::stoul(digits, nullptr, 16)));
                    i += n;
                }
                break;
            }
            default: out += e;  // \" \' \\ and any other character as itself
        }
    }
    return out;
}

}  // namespace

std::string rewrite_aggregates(const std::string& query, std::vector<ConcatColumn>* concat_columns) {
    const std::vector<SparqlToken> t = tokenize_sparql(query);
    auto text = [&](std::size_t k) {
        return std::string_view(query).substr(t[k].begin, t[k].end - t[k].begin);
    };
    auto word = [&](std::size_t k, std::string_view w) {
        if (k >= t.size() || t[k].kind != Kind::Word) return false;
        const std::string_view x = text(k);
        if (x.size() != w.size()) return false;
        for (std::size_t i = 0; i < x.size(); ++i)
            if ((x[i] >= 'a' && x[i] <= 'z' ? x[i] - 32 : x[i]) != w[i]) return false;
        return true;
    };
    auto punct = [&](std::size_t k, std::string_view p) {
        return k < t.size() && t[k].kind == Kind::Punct && text(k) == p;
    };
    std::vector<Edit> edits;
    // The outermost SELECT clause and its ORDER BY, for the GROUP_CONCAT columns.
    std::size_t select = t.size(), where = t.size();
    for (std::size_t k = 0; k < t.size(); ++k) {
        if (select == t.size() && word(k, "SELECT")) select = k;
        if (select != t.size() && punct(k, "{")) {
            where = k;
            break;
        }
    }
    std::size_t order_by = t.size();
    for (std::size_t k = where; k < t.size(); ++k)
        if (word(k, "ORDER")) order_by = k;

    for (std::size_t k = 0; k + 3 < t.size(); ++k) {
        // COUNT ( ?x )
        if (word(k, "COUNT") && punct(k + 1, "(") && t[k + 2].kind == Kind::Variable &&
            punct(k + 3, ")")) {
            const std::string v(text(k + 2));
            edits.push_back({t[k].begin, t[k + 3].end, "SUM(IF(BOUND(" + v + "), 1, 0))"});
            k += 3;
            continue;
        }
        // ( GROUP_CONCAT ( expr ; SEPARATOR = "s" ) AS ?v ), in the outermost SELECT clause
        if (!concat_columns || k <= select || k >= where || !punct(k, "(") ||
            !word(k + 1, "GROUP_CONCAT") || !punct(k + 2, "(") || word(k + 3, "DISTINCT"))
            continue;
        std::size_t j = k + 3;
        int depth = 0;
        while (j < where && !(depth == 0 && (punct(j, ";") || punct(j, ")")))) {
            if (punct(j, "(")) ++depth;
            if (punct(j, ")")) --depth;
            ++j;
        }
        if (j == k + 3 || !punct(j, ";") || !word(j + 1, "SEPARATOR") || !punct(j + 2, "=") ||
            j + 3 >= t.size() || t[j + 3].kind != Kind::String || !punct(j + 4, ")") ||
            !word(j + 5, "AS") || j + 6 >= t.size() || t[j + 6].kind != Kind::Variable ||
            !punct(j + 7, ")"))
            continue;
        const std::string variable(text(j + 6).substr(1));
        // Sorting by the column would sort by its encoded text: left to Rasqal then.
        bool sorted_by = false;
        for (std::size_t m = order_by; m < t.size(); ++m)
            sorted_by = sorted_by || (t[m].kind == Kind::Variable && text(m).substr(1) == variable);
        if (sorted_by) continue;
        const std::string expr = query.substr(t[k + 3].begin, t[j - 1].end - t[k + 3].begin);
        edits.push_back({t[k + 2].begin, t[j + 4].end,
                         "(IF(STR(" + expr + ") = \"\", \"%\", ENCODE_FOR_URI(STR(" + expr + "))))" +
                             std::string(static_cast<std::size_t>(std::count(
                                             query.begin() + static_cast<long>(t[k + 2].begin),
                                             query.begin() + static_cast<long>(t[j + 4].end), '\n')),
                                         '\n')});
        concat_columns->push_back({variable, unescape_string(text(j + 3))});
        k = j + 7;
    }
    if (edits.empty()) return query;
    std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
    std::string out;
    std::size_t at = 0;
    for (const Edit& e : edits) {
        out.append(query, at, e.begin - at);
        out += e.text;
        at = e.end;
    }
    out.append(query, at, std::string::npos);
    return out;
}

std::string join_concat_parts(const std::string& joined, const std::string& separator) {
    std::string out;
    std::size_t start = 0;
    while (true) {
        const std::size_t space = joined.find(' ', start);
        const std::string_view part =
            std::string_view(joined).substr(start, space == std::string::npos ? std::string::npos
                                                                               : space - start);
        if (start > 0) out += separator;
        // A lone "%" (never an encoded text) stands for "" (rewrite_aggregates).
        for (std::size_t i = part == "%" ? 1 : 0; i < part.size(); ++i) {
            auto hex = [](char c) {
                return c >= '0' && c <= '9'   ? c - '0'
                       : c >= 'A' && c <= 'F' ? c - 'A' + 10
                       : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                              : -1;
            };
            if (part[i] == '%' && i + 2 < part.size() && hex(part[i + 1]) >= 0 &&
                hex(part[i + 2]) >= 0) {
                out += static_cast<char>(hex(part[i + 1]) * 16 + hex(part[i + 2]));
                i += 2;
            } else {
                out += part[i];
            }
        }
        if (space == std::string::npos) break;
        start = space + 1;
    }
    return out;
}

}  // namespace geotex::detail
