#include "ontology/detail/sparql_paths.hpp"

#include <algorithm>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "ontology/detail/sparql_tokens.hpp"

namespace geotex::detail {

namespace {

using Kind = SparqlToken::Kind;

struct Path {
    enum class Op { Link, Inverse, Sequence, Alternative, Negated };
    Op op = Op::Link;
    std::string link;                          // Link: the IRI or prefixed name as written
    std::vector<std::unique_ptr<Path>> parts;  // Inverse: 1; Sequence, Alternative: 2 or more
    std::vector<std::pair<bool, std::string>> negated;  // Negated: (inverse?, IRI)
};

/// Thrown where the rewriter cannot read the query; the query then goes to Rasqal unchanged.
struct Malformed {};

const char* const kRdfType = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>";

class PathRewriter {
  public:
    PathRewriter(const std::string& query, std::vector<SparqlToken> tokens, std::string prefix)
        : q_(query), t_(std::move(tokens)), prefix_(std::move(prefix)) {}

    std::vector<TextEdit> run() {
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
    std::vector<TextEdit> edits_;

    std::string_view text(const SparqlToken& t) const {
        return std::string_view(q_).substr(t.begin, t.end - t.begin);
    }
    bool at_end() const { return k_ >= t_.size(); }
    bool is_punct(std::string_view p, std::size_t k) const {
        return k < t_.size() && detail::is_punct(q_, t_[k], p);
    }
    bool is_punct(std::string_view p) const { return is_punct(p, k_); }
    bool is_word(std::string_view w, std::size_t k) const {
        return k < t_.size() && is_keyword(q_, t_[k], w);
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

    /// part (separator part)*: one part alone, else a path `op` over the parts.
    std::unique_ptr<Path> path_list(Path::Op op, std::string_view separator,
                                    std::unique_ptr<Path> (PathRewriter::*part)()) {
        auto first = (this->*part)();
        if (!is_punct(separator)) return first;
        auto list = std::make_unique<Path>();
        list->op = op;
        list->parts.push_back(std::move(first));
        while (is_punct(separator)) {
            ++k_;
            list->parts.push_back((this->*part)());
        }
        return list;
    }

    std::unique_ptr<Path> path_alternative() {
        return path_list(Path::Op::Alternative, "|", &PathRewriter::path_sequence);
    }

    std::unique_ptr<Path> path_sequence() {
        return path_list(Path::Op::Sequence, "/", &PathRewriter::path_inverse);
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
        if (at_end() ||
            !(t_[k_].kind == Kind::Iri || t_[k_].kind == Kind::PrefixedName || is_word("A")))
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
                fail(
                    "a property path inside [ ... ] is not supported by geotex query: name "
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
        const bool has_path = std::any_of(
            list.begin(), list.end(), [](const Predicate& p) { return p.verb.path != nullptr; });
        if (!has_path) return;
        if (subject.complex)
            fail(
                "a property path in a pattern whose subject is [ ... ] or ( ... ) is not "
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
                    fail(
                        "a property path to an object [ ... ] or ( ... ) is not supported by "
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
        replacement += line_breaks(q_, begin, end);
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

std::string rewrite_property_paths(const std::string& query, std::string* fresh_prefix) {
    std::vector<SparqlToken> tokens = tokenize_sparql(query);
    // A prefix that no variable of the query starts with.
    std::string prefix = "_path";
    auto used = [&](const std::string& p) {
        return std::any_of(tokens.begin(), tokens.end(), [&](const SparqlToken& t) {
            return t.kind == Kind::Variable && query.compare(t.begin + 1, p.size(), p) == 0;
        });
    };
    while (used(prefix)) prefix += "_";
    if (fresh_prefix) *fresh_prefix = prefix;

    std::vector<TextEdit> edits;
    try {
        edits = PathRewriter(query, std::move(tokens), prefix).run();
    } catch (const Malformed&) {
        return query;
    }
    return edits.empty() ? query : apply_edits(query, std::move(edits));
}

}  // namespace geotex::detail
