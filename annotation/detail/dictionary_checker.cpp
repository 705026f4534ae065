// The checker's walk over the document, and the readers of values every part uses: map
// keys (with suggestions for typos), texts by language, IRIs; duplicate keys.

#include "annotation/detail/dictionary_checker.hpp"

namespace geotex::dictionary_detail {

void Checker::check_duplicate_keys() {
    for (const YNode& node : n_) {
        if (node.kind != YNode::Kind::Map) continue;
        std::map<std::string, size_t> seen;
        for (size_t k = 0; k < node.items.size(); k += 2) {
            const YNode& key = n_[node.items[k]];
            if (key.kind != YNode::Kind::Scalar) continue;
            const auto [it, fresh] = seen.emplace(key.value, key.offset);
            if (!fresh)
                p_.add(key.offset, "duplicate key " + quoted(key.value) + " (first at line " +
                                       std::to_string(p_.line_of(it->second)) +
                                       "); YAML keeps only one of them: merge or rename");
        }
    }
}

void Checker::check_document(int root, Dictionary& out) {
    if (root < 0 || n_[root].kind == YNode::Kind::Null) {
        p_.add(root < 0 ? 0 : n_[root].offset,
               "empty dictionary: expected a map with the keys 'scheme' and 'features'");
        return;
    }
    if (!expect(root, YNode::Kind::Map, "the dictionary", "a map with 'scheme' and 'features'"))
        return;
    const auto entries = map_entries(root, kTopKeys, "at the top level");
    const bool has_scheme = entries.count("scheme") != 0;
    const bool has_features = entries.count("features") != 0;
    if (!has_scheme) missing(root, "the dictionary", "scheme");
    if (!has_features) missing(root, "the dictionary", "features");
    if (has_scheme) check_scheme(entries.at("scheme"), out);
    // facets before features only for the reading; which facet a feature is in is checked
    // once both are read (finish_facets)
    const bool has_facets = entries.count("facets") != 0;
    if (has_facets) check_facets(entries.at("facets"));
    if (has_features) check_features(entries.at("features"), out);
    if (has_facets)
        finish_facets(out);
    else
        one_facet_per_feature(out);
}

void Checker::missing(int map, const std::string& where, const std::string& key) {
    if (guessed_.count(key)) return;
    p_.add(node(map).offset, where + ": missing required key " + quoted(key));
}

size_t Checker::place(const Entry& e) const {
    return node(e.second).kind == YNode::Kind::Null ? node(e.first).offset : node(e.second).offset;
}

bool Checker::expect(int value, YNode::Kind kind, const std::string& what,
                     const std::string& expected, size_t where) {
    if (node(value).kind == kind) return true;
    p_.add(where == std::string::npos ? node(value).offset : where,
           what + ": expected " + expected + ", found " + kind_name(node(value).kind));
    return false;
}

bool Checker::expect(const Entry& e, YNode::Kind kind, const std::string& what,
                     const std::string& expected) {
    return expect(e.second, kind, what, expected, place(e));
}

std::map<std::string, Entry> Checker::map_entries(int map, const std::vector<std::string>& known,
                                                  const std::string& where) {
    std::map<std::string, Entry> out;
    guessed_.clear();
    const YNode& m = node(map);
    for (size_t k = 0; k + 1 < m.items.size(); k += 2) {
        const YNode& key = node(m.items[k]);
        if (key.kind != YNode::Kind::Scalar) {
            p_.add(key.offset, "a key must be a text, found " + std::string(kind_name(key.kind)));
            continue;
        }
        if (std::find(known.begin(), known.end(), key.value) == known.end()) {
            std::vector<std::pair<std::string, std::string>> candidates;
            for (const auto& w : known) candidates.emplace_back(w, w);
            const std::string guess = closest(key.value, candidates);
            guessed_.insert(guess);
            p_.add(key.offset, "unknown key " + quoted(key.value) + " " + where +
                                   (guess.empty() ? " (known keys: " + join(known) + ")"
                                                  : "; did you mean " + quoted(guess) + "?"));
            continue;
        }
        out.emplace(key.value, Entry{m.items[k], m.items[k + 1]});  // first of duplicates
    }
    return out;
}

bool Checker::text(const Entry& e, const std::string& what, std::string& out, bool multi_line) {
    if (!expect(e, YNode::Kind::Scalar, what, "a text")) return false;
    const YNode& v = node(e.second);
    if (v.value.empty()) {
        p_.add(v.offset, what + " is empty");
        return false;
    }
    const bool escaped = v.tag == "!" && v.offset < text_.size() && text_[v.offset] == '"';
    const long cp = forbidden_control(v.value, multi_line, escaped);
    if (cp >= 0) {
        p_.add(v.offset, what + " contains the control character " + code_point_name(cp) +
                             (multi_line ? "" : " (this text is one line)"));
        return false;
    }
    out = v.value;
    return true;
}

void Checker::texts_by_language(const Entry& e, const std::string& what,
                                std::map<std::string, std::string>& out, bool multi_line,
                                const std::vector<std::string>* required,
                                std::map<std::string, size_t>* offsets) {
    if (!expect(e, YNode::Kind::Map, what, "a map from language tag to text (en: ..., fr: ...)"))
        return;
    const YNode& m = node(e.second);
    for (size_t k = 0; k + 1 < m.items.size(); k += 2) {
        const YNode& key = node(m.items[k]);
        if (key.kind != YNode::Kind::Scalar || !is_language_tag(key.value)) {
            p_.add(key.offset, what + ": " +
                                   (key.kind == YNode::Kind::Scalar ? quoted(key.value)
                                                                    : std::string("this key")) +
                                   " is not a language tag (e.g. en, fr, pt-BR)");
            continue;
        }
        std::string value;
        if (text({m.items[k], m.items[k + 1]}, what + " in " + quoted(key.value), value,
                 multi_line)) {
            out.emplace(key.value, value);
            if (offsets) offsets->emplace(key.value, node(m.items[k + 1]).offset);
        }
    }
    if (!required) return;
    std::vector<std::string> absent;
    for (const auto& lang : *required) {
        bool present = false;
        for (size_t k = 0; k + 1 < m.items.size(); k += 2)
            present = present || node(m.items[k]).value == lang;
        if (!present) absent.push_back(quoted(lang));
    }
    if (!absent.empty())
        p_.add(m.offset, what + ": no text in " + join(absent, " and ") +
                             " (every language listed in scheme.languages is required)");
}

void Checker::iris(const Entry& e, const std::string& what, std::vector<std::string>& out,
                   const std::string& expected, bool web_only) {
    std::vector<int> items;
    if (node(e.second).kind == YNode::Kind::Sequence) {
        items = node(e.second).items;
        if (items.empty()) p_.add(place(e), what + " is empty: give an IRI or leave the key out");
    } else if (expect(e, YNode::Kind::Scalar, what, expected)) {
        items.push_back(e.second);
    }
    for (int item : items) {
        std::string iri;
        if (!expect(item, YNode::Kind::Scalar, what, "an IRI") || !text({e.first, item}, what, iri))
            continue;
        const std::string why = iri_problem(iri);
        if (!why.empty()) {
            p_.add(node(item).offset, what + " " + quoted(iri) + " " + why);
            continue;
        }
        // A prefixed name such as aat:300000000 is an absolute IRI by syntax, but not the
        // concept the curator meant: matches point at concepts published on the web.
        if (web_only && iri.rfind("http://", 0) != 0 && iri.rfind("https://", 0) != 0) {
            p_.add(node(item).offset,
                   what + " " + quoted(iri) +
                       " is not an http:// or https:// IRI (write the whole IRI of the "
                       "concept, e.g. http://vocab.getty.edu/aat/ followed by its number)");
            continue;
        }
        if (std::find(out.begin(), out.end(), iri) != out.end()) {
            p_.add(node(item).offset, what + " lists " + quoted(iri) + " twice");
            continue;
        }
        out.push_back(iri);
    }
}

void Checker::warn(size_t offset, std::string message) {
    const auto [line, column] = p_.places->at(offset);
    warnings.push_back({line, column, std::move(message)});
}

std::string Checker::place_text(size_t offset) const {
    const auto [line, column] = p_.places->at(offset);
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

}  // namespace geotex::dictionary_detail
