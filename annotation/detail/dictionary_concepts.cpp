// The features of a dictionary and their concepts: ids, intervals (bounds as written, at
// most 15 significant digits), overlaps, relief, labels unique per language.

#include "annotation/detail/dictionary_checker.hpp"

namespace geotex::dictionary_detail {

void Checker::check_features(const Entry& e, Dictionary& out) {
    if (!expect(e, YNode::Kind::Map, "features", "a map from feature id to a list of concepts"))
        return;
    const YNode& m = node(e.second);
    if (m.items.empty()) p_.add(m.offset, "features is empty: the dictionary has no concept");
    std::vector<ConceptDraft> drafts;
    for (size_t k = 0; k + 1 < m.items.size(); k += 2) {
        const YNode& key = node(m.items[k]);
        if (key.kind != YNode::Kind::Scalar) {
            p_.add(key.offset,
                   "a feature id must be a text, found " + std::string(kind_name(key.kind)));
            continue;
        }
        const int feature = feature_index(key.value);
        if (feature < 0)
            p_.add(key.offset, unknown_feature(key.value, ""));
        else if (feature_key_[feature] == std::string::npos)
            feature_key_[feature] = key.offset;
        const Entry list{m.items[k], m.items[k + 1]};
        if (!expect(list, YNode::Kind::Sequence, "feature " + quoted(key.value),
                    "a list of concepts (each '- id: ...')"))
            continue;
        int position = 0;
        for (int item : node(list.second).items) {
            ++position;
            ConceptDraft d;
            d.concept_.feature = feature;
            if (check_concept(item, key.value, position, d)) drafts.push_back(std::move(d));
        }
    }
    check_unique_ids(drafts);
    check_overlaps(drafts);
    check_unique_labels(drafts);
    for (auto& d : drafts)
        if (d.concept_.feature >= 0) out.concepts.push_back(std::move(d.concept_));
    std::stable_sort(out.concepts.begin(), out.concepts.end(),
                     [](const DictionaryConcept& a, const DictionaryConcept& b) {
                         return a.feature != b.feature ? a.feature < b.feature : a.lower < b.lower;
                     });
}

bool Checker::check_concept(int item, const std::string& feature, int position, ConceptDraft& d) {
    DictionaryConcept& c = d.concept_;
    const YNode& m = node(item);
    std::string where = "concept " + std::to_string(position) + " of " + quoted(feature);
    if (!expect(item, YNode::Kind::Map, where, "a map with id, interval and labels")) return false;
    const auto [line, column] = p_.places->at(m.offset);
    c.line = line;
    c.column = column;
    const auto entries = map_entries(item, kConceptKeys, "in a concept");
    if (entries.count("id") && text(entries.at("id"), where + ": id", c.id)) {
        d.id_offset = node(entries.at("id").second).offset;
        if (!is_id(c.id))
            p_.add(node(entries.at("id").second).offset,
                   "concept id " + quoted(c.id) +
                       " may hold only letters, digits, '-', '_' and '.' (it goes into IRIs; "
                       "kebab-case is the convention)");
        where = "concept " + quoted(c.id);
    }
    for (const char* key : {"id", "interval", "labels"})
        if (!entries.count(key)) missing(item, where, key);
    if (entries.count("interval")) d.bounds_ok = check_interval(entries.at("interval"), where, d);
    if (entries.count("labels"))
        texts_by_language(entries.at("labels"), where + ": labels", c.labels, false,
                          languages_ok_ ? &languages_ : nullptr, &d.label_offsets);
    if (entries.count("relief")) check_relief(entries.at("relief"), where, c);
    if (entries.count("definition"))
        texts_by_language(entries.at("definition"), where + ": definition", c.definitions, true,
                          nullptr);
    if (entries.count("source")) text(entries.at("source"), where + ": source", c.source, true);
    const char* list = "an IRI or a list of IRIs (http://vocab.getty.edu/aat/...)";
    if (entries.count("exactMatch"))
        iris(entries.at("exactMatch"), where + ": exactMatch", c.exact_matches, list, true);
    if (entries.count("closeMatch"))
        iris(entries.at("closeMatch"), where + ": closeMatch", c.close_matches, list, true);
    return true;
}

bool Checker::check_interval(const Entry& e, const std::string& where, ConceptDraft& d) {
    if (!expect(e, YNode::Kind::Sequence, where + ": interval", "[lower, upper]")) return false;
    const YNode& list = node(e.second);
    d.interval_offset = list.offset;
    if (list.items.size() != 2) {
        p_.add(list.offset, where + ": interval has " + std::to_string(list.items.size()) +
                                " values; expected [lower, upper]");
        return false;
    }
    const Bound lower = bound(list.items[0], where, "lower");
    const Bound upper = bound(list.items[1], where, "upper");
    if (!lower.ok || !upper.ok) return false;
    DictionaryConcept& c = d.concept_;
    c.lower = lower.value;
    c.upper = upper.value;
    c.lower_text = lower.text;
    c.upper_text = upper.text;
    if (!(c.lower < c.upper)) {
        p_.add(list.offset, where + ": interval " + interval_text(c) +
                                " is empty: the lower bound must be below the upper bound");
        return false;
    }
    return true;
}

Bound Checker::bound(int item, const std::string& where, const char* which) {
    const YNode& v = node(item);
    const std::string what = where + ": " + which + " bound";
    Bound b;
    if (v.kind != YNode::Kind::Scalar) {
        p_.add(v.offset, what + " must be a number or .inf/-.inf, found " + kind_name(v.kind));
        return b;
    }
    if (v.tag != "?" && v.tag != "tag:yaml.org,2002:float" && v.tag != "tag:yaml.org,2002:int") {
        p_.add(v.offset, what + " " + quoted(v.value) +
                             " is written as text (quoted or tagged); write the number bare");
        return b;
    }
    const std::string& s = v.value;
    if (s == ".inf" || s == ".Inf" || s == ".INF" || s == "+.inf" || s == "+.Inf" || s == "+.INF") {
        b = {true, std::numeric_limits<double>::infinity(), ""};
        return b;
    }
    if (s == "-.inf" || s == "-.Inf" || s == "-.INF") {
        b = {true, -std::numeric_limits<double>::infinity(), ""};
        return b;
    }
    std::string text;
    if (!decimal_text(s, text)) {
        std::string lower = s;
        for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        const bool infinite_word = lower.find("inf") != std::string::npos;
        p_.add(v.offset, what + " " + quoted(s) + " is not a number" +
                             (infinite_word ? " (YAML writes infinity as .inf or -.inf)"
                                            : " (write a decimal such as 0.05, -200 or 1e-3, "
                                              "or .inf / -.inf)"));
        return b;
    }
    double value = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
    if (r.ec != std::errc() || !std::isfinite(value)) {
        p_.add(v.offset, what + " " + quoted(s) + " is out of the range of a double");
        return b;
    }
    // Beyond 15 significant digits two different decimals can be the same double: an
    // upper bound 0.3000...01 (55 digits) and its neighbour's lower bound 0.3 overlap as
    // decimals but not as doubles, and the overlap would go unseen. Up to 15 (DBL_DIG)
    // distinct decimals are distinct doubles in the same order, so comparing the doubles
    // is comparing the decimals written. Subnormal doubles hold fewer digits.
    const auto first = text.find_first_of("123456789");
    std::size_t digits = 0;
    if (first != std::string::npos)
        for (std::size_t k = first; k <= text.find_last_of("123456789"); ++k)
            digits += std::isdigit(static_cast<unsigned char>(text[k])) ? 1 : 0;
    if (digits > 15) {
        p_.add(v.offset, what + " " + quoted(s) + " has " + std::to_string(digits) +
                             " significant digits; a bound has at most 15, the digits a "
                             "double keeps (beyond them distinct bounds can be the same "
                             "number and an overlap would go unseen)");
        return b;
    }
    if (value != 0 && std::fabs(value) < std::numeric_limits<double>::min()) {
        p_.add(v.offset,
               what + " " + quoted(s) + " is below the smallest normal double (2.2e-308)");
        return b;
    }
    b = {true, value, text};
    return b;
}

std::string Checker::bound_text(double v, const std::string& text) {
    return text.empty() ? (v < 0 ? "-.inf" : ".inf") : text;
}

std::string Checker::interval_text(const DictionaryConcept& c) {
    return "[" + bound_text(c.lower, c.lower_text) + ", " + bound_text(c.upper, c.upper_text) + ")";
}

void Checker::check_unique_ids(const std::vector<ConceptDraft>& drafts) {
    std::map<std::string, size_t> first;
    for (const auto& d : drafts) {
        if (d.concept_.id.empty()) continue;
        const auto [it, fresh] = first.emplace(d.concept_.id, d.id_offset);
        if (!fresh)
            p_.add(d.id_offset, "duplicate concept id " + quoted(d.concept_.id) +
                                    " (first at line " + std::to_string(p_.line_of(it->second)) +
                                    "); concept ids are unique in the dictionary");
    }
}

void Checker::check_overlaps(const std::vector<ConceptDraft>& drafts) {
    std::vector<const ConceptDraft*> ok;
    for (const auto& d : drafts)
        if (d.bounds_ok && d.concept_.feature >= 0) ok.push_back(&d);
    // file order: each pair is reported once, at the later of the two
    for (size_t j = 0; j < ok.size(); ++j)
        for (size_t i = 0; i < j; ++i) {
            const DictionaryConcept& a = ok[i]->concept_;
            const DictionaryConcept& b = ok[j]->concept_;
            if (a.feature != b.feature || !(a.lower < b.upper && b.lower < a.upper)) continue;
            p_.add(ok[j]->interval_offset, "interval " + interval_text(b) + " of " + quoted(b.id) +
                                               " overlaps " + interval_text(a) + " of " +
                                               quoted(a.id) + " (line " + std::to_string(a.line) +
                                               "); intervals of one feature must be disjoint");
        }
}

std::string Checker::unknown_feature(const std::string& id, const std::string& where) {
    const std::string guess = closest(id, feature_spellings());
    return "unknown feature " + quoted(id) + where +
           (guess.empty() ? " (the " + std::to_string(kNumFeatures) +
                                " feature ids are listed in docs/features.md)"
                          : "; did you mean " + quoted(guess) + "?");
}

void Checker::check_relief(const Entry& e, const std::string& where, DictionaryConcept& c) {
    std::string value;
    if (!text(e, where + ": relief", value)) return;
    for (const auto& [word, relief] : kReliefs)
        if (value == word) {
            c.relief = relief;
            return;
        }
    std::vector<std::pair<std::string, std::string>> candidates;
    for (const auto& [word, relief] : kReliefs) candidates.emplace_back(word, word);
    const std::string guess = closest(value, candidates);
    p_.add(node(e.second).offset,
           where + ": unknown relief " + quoted(value) +
               (guess.empty() ? "" : "; did you mean " + quoted(guess) + "?") +
               " (write 'raised' for a word true only of a raised detail, 'engraved' for one "
               "true only of an engraving, or leave the key out)");
}

std::string Checker::label_key(const std::string& label) {
    std::string key = label;
    for (char& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return key;
}

void Checker::check_unique_labels(const std::vector<ConceptDraft>& drafts) {
    std::map<std::pair<std::string, std::string>, std::pair<const ConceptDraft*, size_t>> first;
    for (const auto& d : drafts)
        for (const auto& [lang, offset] : d.label_offsets) {
            const std::string& label = d.concept_.labels.at(lang);
            const auto [it, fresh] =
                first.emplace(std::make_pair(lang, label_key(label)), std::make_pair(&d, offset));
            if (fresh) {
                concept_labels_.emplace(it->first, ConceptLabel{d.concept_.id, offset, label});
                continue;
            }
            const DictionaryConcept& other = it->second.first->concept_;
            p_.add(offset, (d.concept_.id.empty() ? std::string("a concept")
                                                  : "concept " + quoted(d.concept_.id)) +
                               ": label " + quoted(label) + " in " + quoted(lang) +
                               " is also the label of " +
                               (other.id.empty() ? std::string("another concept")
                                                 : "concept " + quoted(other.id)) +
                               " at " + place_text(it->second.second) +
                               "; two concepts with one label cannot be told apart");
        }
}

std::string Checker::concept_name(const std::string& id) {
    return id.empty() ? std::string("a concept") : "concept " + quoted(id);
}

}  // namespace geotex::dictionary_detail
