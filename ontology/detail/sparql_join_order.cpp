#include "ontology/detail/sparql_join_order.hpp"

#include <algorithm>
#include <map>
#include <string_view>
#include <utility>
#include <vector>

#include "ontology/detail/sparql_tokens.hpp"

namespace geotex::detail {

namespace {

using Kind = SparqlToken::Kind;

const char* const kRdfTypeIri = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type";

/// One part of a triple pattern as written.
struct Part {
    std::size_t begin = 0, end = 0;  // byte range in the query
    std::string variable;            // a variable's or blank node's name; empty: a constant
    std::string iri;                 // a constant IRI, resolved; empty otherwise
};

struct Pattern {
    Part s, p, o;
};

/// Thrown where the group is not one this file reorders; it then stays as written.
struct NotReordered {};

class GroupReader {
  public:
    GroupReader(const std::string& q, const std::vector<SparqlToken>& t,
                const std::map<std::string, std::string>& prefixes)
        : q_(q), t_(t), prefixes_(prefixes) {}

    /// Reads the tokens strictly between `open` and `close` (a '{' and its '}').
    void read(std::size_t open, std::size_t close) {
        k_ = open + 1;
        end_ = close;
        while (k_ < end_) {
            if (is_word("FILTER")) {
                filter();
            } else {
                triples();
            }
            if (k_ < end_ && punct(".")) ++k_;
        }
    }

    std::vector<Pattern> patterns;
    std::vector<std::pair<std::size_t, std::size_t>> filters;  // byte ranges

  private:
    const std::string& q_;
    const std::vector<SparqlToken>& t_;
    const std::map<std::string, std::string>& prefixes_;
    std::size_t k_ = 0, end_ = 0;

    std::string_view text(std::size_t k) const { return token_text(q_, t_[k]); }
    bool punct(std::string_view p) const { return k_ < end_ && is_punct(q_, t_[k_], p); }
    bool is_word(std::string_view w) const { return k_ < end_ && is_keyword(q_, t_[k_], w); }

    void filter() {
        const std::size_t begin = t_[k_].begin;
        ++k_;
        // FILTER ( ... ), or FILTER name( ... )
        if (k_ < end_ && (t_[k_].kind == Kind::Word || t_[k_].kind == Kind::PrefixedName ||
                          t_[k_].kind == Kind::Iri))
            ++k_;
        if (!punct("(")) throw NotReordered{};
        int depth = 0;
        do {
            if (k_ >= end_) throw NotReordered{};
            if (is_punct(q_, t_[k_], "(")) ++depth;
            if (is_punct(q_, t_[k_], ")")) --depth;
            if (is_punct(q_, t_[k_], "{") || is_punct(q_, t_[k_], "}"))
                throw NotReordered{};  // EXISTS { ... }
            ++k_;
        } while (depth > 0);
        filters.emplace_back(begin, t_[k_ - 1].end);
    }

    void triples() {
        const Part s = term(false);
        while (true) {
            const Part p = term(true);
            while (true) {
                patterns.push_back({s, p, term(false)});
                if (!punct(",")) break;
                ++k_;
            }
            if (!punct(";")) return;
            while (punct(";")) ++k_;
            if (k_ >= end_ || punct(".") || is_word("FILTER")) return;
        }
    }

    Part term(bool predicate) {
        if (k_ >= end_) throw NotReordered{};
        Part part;
        part.begin = t_[k_].begin;
        const std::string_view x = text(k_);
        switch (t_[k_].kind) {
            case Kind::Variable:
                part.variable = std::string(x.substr(1));
                break;
            case Kind::BlankLabel:
                if (predicate) throw NotReordered{};
                part.variable = std::string(x);  // "_:b", never a variable's name
                break;
            case Kind::Iri:
                // A relative IRI resolves against the base: its statistics are unknown.
                if (x.find(':') != std::string_view::npos)
                    part.iri = std::string(x.substr(1, x.size() - 2));
                break;
            case Kind::PrefixedName: {
                const std::size_t colon = x.find(':');
                const auto found = prefixes_.find(std::string(x.substr(0, colon + 1)));
                if (found == prefixes_.end()) throw NotReordered{};
                // A local part with escapes is left unresolved (statistics unknown).
                if (x.find_first_of("\\%") == std::string_view::npos)
                    part.iri = found->second + std::string(x.substr(colon + 1));
                break;
            }
            case Kind::Word:
                if (predicate && x == "a") {
                    part.iri = kRdfTypeIri;
                } else if (predicate || (x != "true" && x != "false")) {
                    throw NotReordered{};
                }
                break;
            case Kind::Number:
                if (predicate) throw NotReordered{};
                break;
            case Kind::String:
                if (predicate) throw NotReordered{};
                if (k_ + 1 < end_ && t_[k_ + 1].kind == Kind::LangTag) {
                    ++k_;
                } else if (k_ + 2 < end_ && is_punct(q_, t_[k_ + 1], "^^") &&
                           (t_[k_ + 2].kind == Kind::Iri ||
                            t_[k_ + 2].kind == Kind::PrefixedName)) {
                    k_ += 2;
                }
                break;
            default:
                throw NotReordered{};  // [ ], ( ), a signed number, a keyword
        }
        part.end = t_[k_].end;
        ++k_;
        return part;
    }
};

/// The written order with each functional pattern moved to just after what fixes it.
std::vector<std::size_t> hoisted_order(const std::vector<Pattern>& patterns,
                                       const PatternCost& cost) {
    std::vector<std::string> bound;
    auto fixed = [&](const Part& x) {
        return x.variable.empty() ||
               std::find(bound.begin(), bound.end(), x.variable) != bound.end();
    };
    std::vector<bool> done(patterns.size(), false);
    std::vector<std::size_t> order;
    auto take = [&](std::size_t i) {
        done[i] = true;
        order.push_back(i);
        for (const Part* x : {&patterns[i].s, &patterns[i].p, &patterns[i].o})
            if (!x->variable.empty() && !fixed(*x)) bound.push_back(x->variable);
    };
    for (std::size_t next = 0; next < patterns.size(); ++next) {
        if (done[next]) continue;
        take(next);
        // Every pattern that has become functional, in written order, until none is left.
        for (bool moved = true; moved;) {
            moved = false;
            for (std::size_t i = next + 1; i < patterns.size(); ++i) {
                if (done[i]) continue;
                const Pattern& x = patterns[i];
                // A variable predicate is left where it is written.
                if (!x.p.variable.empty()) continue;
                const bool s = fixed(x.s), o = fixed(x.o);
                if ((!s && !o) || cost(x.p.iri, s, o) > 1.0) continue;
                take(i);
                moved = true;
            }
        }
    }
    return order;
}

}  // namespace

std::string order_triple_patterns(const std::string& query, const PatternCost& cost) {
    const std::vector<SparqlToken> t = tokenize_sparql(query);
    auto text = [&](std::size_t k) { return token_text(query, t[k]); };
    auto punct = [&](std::size_t k, std::string_view p) {
        return k < t.size() && is_punct(query, t[k], p);
    };
    std::map<std::string, std::string> prefixes;
    for (std::size_t k = 0; k + 2 < t.size(); ++k) {
        if (is_keyword(query, t[k], "PREFIX") && t[k + 1].kind == Kind::PrefixedName &&
            t[k + 2].kind == Kind::Iri) {
            const std::string_view iri = text(k + 2);
            prefixes[std::string(text(k + 1))] = std::string(iri.substr(1, iri.size() - 2));
        }
    }

    std::vector<TextEdit> edits;
    std::vector<std::size_t> open;
    for (std::size_t k = 0; k < t.size(); ++k) {
        if (punct(k, "{")) {
            open.push_back(k);
            continue;
        }
        if (!punct(k, "}") || open.empty()) continue;
        const std::size_t from = open.back();
        open.pop_back();
        // Innermost groups only, and not a VALUES block (after VALUES ?x or VALUES (...)).
        bool innermost = true;
        for (std::size_t j = from + 1; j < k; ++j) innermost = innermost && !punct(j, "{");
        if (!innermost || k == from + 1) continue;
        if (from > 0 && (punct(from - 1, ")") || t[from - 1].kind == Kind::Variable ||
                         t[from - 1].kind == Kind::Iri || t[from - 1].kind == Kind::PrefixedName))
            continue;  // VALUES (?x) { or VALUES ?x {; GRAPH ?g { and GRAPH <g> { match nothing
        GroupReader reader(query, t, prefixes);
        try {
            reader.read(from, k);
        } catch (const NotReordered&) {
            continue;
        }
        const std::vector<std::size_t> order = hoisted_order(reader.patterns, cost);
        bool same = true;
        for (std::size_t i = 0; i < order.size(); ++i) same = same && order[i] == i;
        if (same) continue;
        auto piece = [&](const Part& x) { return query.substr(x.begin, x.end - x.begin); };
        std::string body = " ";
        for (std::size_t i : order) {
            const Pattern& x = reader.patterns[i];
            body += piece(x.s) + " " + piece(x.p) + " " + piece(x.o) + " . ";
        }
        for (const auto& [b, e] : reader.filters) body += query.substr(b, e - b) + " ";
        const std::size_t begin = t[from].end, end = t[k].begin;
        edits.push_back({begin, end, body + line_breaks(query, begin, end)});
    }
    return edits.empty() ? query : apply_edits(query, std::move(edits));
}

}  // namespace geotex::detail
