#include "annotation/dictionary.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "annotation/detail/dictionary_text.hpp"
#include "annotation/digest.hpp"
#include "annotation/yaml_tree.hpp"
#include "geometry/detail/text.hpp"
#include "geometry/errors.hpp"
#include "geometry/feature_table.hpp"

namespace geotex {

const DictionaryConcept* Dictionary::find(int feature, double value) const {
    if (std::isnan(value)) return nullptr;
    // concepts are sorted by (feature, lower) and the intervals of one feature are disjoint,
    // so the candidate is the last concept of the feature whose lower bound is <= value.
    const auto by_feature_then_lower = [](const DictionaryConcept& c,
                                          const std::pair<int, double>& key) {
        return c.feature < key.first || (c.feature == key.first && c.lower <= key.second);
    };
    const auto after = std::lower_bound(concepts.begin(), concepts.end(),
                                        std::make_pair(feature, value), by_feature_then_lower);
    if (after == concepts.begin()) return nullptr;
    const DictionaryConcept& c = *std::prev(after);
    if (c.feature != feature || !(c.lower <= value && value < c.upper)) return nullptr;
    return &c;
}

namespace {

using namespace yaml_detail;
using namespace dictionary_detail;
using detail::code_point_name;
using detail::is_calendar_date;
using detail::is_language_tag;

// ---- numbers -------------------------------------------------------------------------------

struct Bound {
    bool ok = false;
    double value = 0;
    std::string text;  // xsd:decimal lexical form, "" for an infinity
};

// ---- the checker ---------------------------------------------------------------------------

using Entry = std::pair<int, int>;  // key node, value node

const std::vector<std::string> kTopKeys = {"scheme", "facets", "features"};
const std::vector<std::string> kSchemeKeys = {"id",        "version", "namespace", "title",
                                              "languages", "creator", "license",   "modified"};
const std::vector<std::string> kRequiredSchemeKeys = {"id", "version", "namespace", "title",
                                                      "languages"};
const std::vector<std::string> kFacetKeys = {"labels", "features"};
const std::vector<std::string> kConceptKeys = {"id",     "interval", "labels",     "definition",
                                               "source", "relief",   "exactMatch", "closeMatch"};
const std::vector<std::pair<std::string, Relief>> kReliefs = {{"raised", Relief::Raised},
                                                              {"engraved", Relief::Engraved}};

/// Other spellings curators may use for a feature (the paper's names), to suggest the id.
const std::vector<std::pair<std::string, std::string>>& feature_spellings() {
    static const std::vector<std::pair<std::string, std::string>> spellings = [] {
        std::vector<std::pair<std::string, std::string>> s;
        for (const char* id : kFeatureIds) s.emplace_back(id, id);
        const std::pair<const char*, const char*> aliases[] = {
            {"perimeter", "contour_perimeter"},
            {"perimeter_length", "contour_perimeter"},
            {"sphericity", "contour_sphericity"},
            {"local_diameter", "local_diameter_mean"},
            {"normalised_area", "area"},
            {"normalized_area", "area"},
            {"squared_perimeter_area_ratio", "perimeter2_area_ratio"},
            {"squared_perimeter_to_area_ratio", "perimeter2_area_ratio"},
            {"pca_1", "pca_variance_1"},
            {"pca_2", "pca_variance_2"},
            {"pca_3", "pca_variance_3"},
            {"gaussian_curvature", "gaussian_curvature_mean"},
            {"shape_index", "shape_index_mean"},
            {"curvature_index_mean", "curvedness_mean"},
            {"curvature_index_std", "curvedness_std"},
            {"curvature_index", "curvedness_mean"},
            {"curvedness", "curvedness_mean"},
            {"depth", "depth_mean"},
        };
        for (const auto& [alias, id] : aliases) s.emplace_back(alias, id);
        return s;
    }();
    return spellings;
}

struct ConceptDraft {
    DictionaryConcept concept_;
    bool bounds_ok = false;
    size_t interval_offset = 0;
    size_t id_offset = 0;
    std::map<std::string, size_t> label_offsets;  // language -> place of the label text
};

struct FacetDraft {
    DictionaryFacet facet;
    std::vector<size_t> feature_offsets;          // place of each entry of facet.features
    std::map<std::string, size_t> label_offsets;  // language -> place of the label text
};

class Checker {
  public:
    Checker(std::string_view text, const std::vector<YNode>& nodes, Problems& problems)
        : text_(text), n_(nodes), p_(problems) {}

    void check_duplicate_keys() {
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

    void check_document(int root, Dictionary& out) {
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

    /// What loads but deserves a look, sorted by place.
    std::vector<DictionaryProblem> warnings;

  private:
    const YNode& node(int i) const { return n_[static_cast<size_t>(i)]; }

    /// Reports a required key that is absent, unless an unknown key of the same map was taken
    /// for a typo of it (that problem already says "did you mean").
    void missing(int map, const std::string& where, const std::string& key) {
        if (guessed_.count(key)) return;
        p_.add(node(map).offset, where + ": missing required key " + quoted(key));
    }

    /// Place to report a problem about the value of an entry: the value, or its key when the
    /// value is empty (an empty value has no place of its own).
    size_t place(const Entry& e) const {
        return node(e.second).kind == YNode::Kind::Null ? node(e.first).offset
                                                        : node(e.second).offset;
    }

    bool expect(int value, YNode::Kind kind, const std::string& what, const std::string& expected,
                size_t where = std::string::npos) {
        if (node(value).kind == kind) return true;
        p_.add(where == std::string::npos ? node(value).offset : where,
               what + ": expected " + expected + ", found " + kind_name(node(value).kind));
        return false;
    }
    bool expect(const Entry& e, YNode::Kind kind, const std::string& what,
                const std::string& expected) {
        return expect(e.second, kind, what, expected, place(e));
    }

    /// The entries of a map by key; unknown keys are reported with the closest known one.
    std::map<std::string, Entry> map_entries(int map, const std::vector<std::string>& known,
                                             const std::string& where) {
        std::map<std::string, Entry> out;
        guessed_.clear();
        const YNode& m = node(map);
        for (size_t k = 0; k + 1 < m.items.size(); k += 2) {
            const YNode& key = node(m.items[k]);
            if (key.kind != YNode::Kind::Scalar) {
                p_.add(key.offset,
                       "a key must be a text, found " + std::string(kind_name(key.kind)));
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

    /// A text value (one line unless `multi_line`); reports and returns false otherwise.
    bool text(const Entry& e, const std::string& what, std::string& out, bool multi_line = false) {
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

    /// A map language tag -> text; checks the tags and, when `required` is given, that every
    /// required language is there.
    void texts_by_language(const Entry& e, const std::string& what,
                           std::map<std::string, std::string>& out, bool multi_line,
                           const std::vector<std::string>* required,
                           std::map<std::string, size_t>* offsets = nullptr) {
        if (!expect(e, YNode::Kind::Map, what,
                    "a map from language tag to text (en: ..., fr: ...)"))
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

    void check_scheme(const Entry& e, Dictionary& out) {
        if (!expect(e, YNode::Kind::Map, "scheme",
                    "a map with id, version, namespace, title and languages"))
            return;
        const auto entries = map_entries(e.second, kSchemeKeys, "in 'scheme'");
        for (const auto& key : kRequiredSchemeKeys)
            if (!entries.count(key)) missing(e.second, "scheme", key);
        if (entries.count("id") && text(entries.at("id"), "scheme.id", out.id) && !is_id(out.id))
            p_.add(node(entries.at("id").second).offset,
                   "scheme.id " + quoted(out.id) +
                       " may hold only letters, digits, '-', '_' and '.' (it goes into IRIs)");
        if (entries.count("version")) text(entries.at("version"), "scheme.version", out.version);
        if (entries.count("namespace") &&
            text(entries.at("namespace"), "scheme.namespace", out.namespace_iri)) {
            const std::string why = namespace_problem(out.namespace_iri);
            if (!why.empty())
                p_.add(node(entries.at("namespace").second).offset,
                       "scheme.namespace " + quoted(out.namespace_iri) + " " + why);
        }
        if (entries.count("languages")) check_languages(entries.at("languages"), out);
        if (entries.count("title"))
            texts_by_language(entries.at("title"), "scheme.title", out.titles, false,
                              languages_ok_ ? &out.languages : nullptr);
        if (entries.count("creator"))
            iris(entries.at("creator"), "scheme.creator", out.creators,
                 "an IRI or a list of IRIs (https://w3id.org/geotex/)");
        if (entries.count("license")) {
            std::vector<std::string> license;
            // One licence: a list would leave open which one applies.
            if (expect(entries.at("license"), YNode::Kind::Scalar, "scheme.license",
                       "one IRI (e.g. https://creativecommons.org/licenses/by/4.0/)"))
                iris(entries.at("license"), "scheme.license", license, "");
            if (!license.empty()) out.license = license.front();
        }
        if (entries.count("modified")) check_modified(entries.at("modified"), out);
    }

    /// An IRI, or a list of them (`expected` says so; "" when only one is allowed and the
    /// caller checked that): each absolute as RDF needs it, none twice.
    void iris(const Entry& e, const std::string& what, std::vector<std::string>& out,
              const std::string& expected, bool web_only = false) {
        std::vector<int> items;
        if (node(e.second).kind == YNode::Kind::Sequence) {
            items = node(e.second).items;
            if (items.empty())
                p_.add(place(e), what + " is empty: give an IRI or leave the key out");
        } else if (expect(e, YNode::Kind::Scalar, what, expected)) {
            items.push_back(e.second);
        }
        for (int item : items) {
            std::string iri;
            if (!expect(item, YNode::Kind::Scalar, what, "an IRI") ||
                !text({e.first, item}, what, iri))
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

    /// The date of this version, as dcterms:modified (an xsd:date) says it. Unquoted, YAML 1.1
    /// would read it as a timestamp; yaml-cpp keeps the text, which is all we need.
    void check_modified(const Entry& e, Dictionary& out) {
        std::string value;
        if (!text(e, "scheme.modified", value)) return;
        if (!is_calendar_date(value)) {
            p_.add(node(e.second).offset,
                   "scheme.modified " + quoted(value) +
                       " is not a date: write the day this version was made as YYYY-MM-DD "
                       "(e.g. 2026-12-01)");
            return;
        }
        out.modified = value;
    }

    void check_languages(const Entry& e, Dictionary& out) {
        if (!expect(e, YNode::Kind::Sequence, "scheme.languages",
                    "a list of language tags ([en, fr])"))
            return;
        const YNode& list = node(e.second);
        bool ok = true;
        if (list.items.empty()) {
            p_.add(list.offset, "scheme.languages is empty: list at least one language tag");
            ok = false;
        }
        for (int item : list.items) {
            const YNode& v = node(item);
            if (v.kind != YNode::Kind::Scalar || !is_language_tag(v.value)) {
                p_.add(v.offset,
                       "scheme.languages: " +
                           (v.kind == YNode::Kind::Scalar ? quoted(v.value)
                                                          : std::string(kind_name(v.kind))) +
                           " is not a language tag (e.g. en, fr, pt-BR)");
                ok = false;
            } else if (std::find(out.languages.begin(), out.languages.end(), v.value) !=
                       out.languages.end()) {
                p_.add(v.offset, "scheme.languages lists " + quoted(v.value) + " twice");
            } else {
                out.languages.push_back(v.value);
            }
        }
        languages_ok_ = ok;
        languages_ = out.languages;
    }

    void check_features(const Entry& e, Dictionary& out) {
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
                             return a.feature != b.feature ? a.feature < b.feature
                                                           : a.lower < b.lower;
                         });
    }

    bool check_concept(int item, const std::string& feature, int position, ConceptDraft& d) {
        DictionaryConcept& c = d.concept_;
        const YNode& m = node(item);
        std::string where = "concept " + std::to_string(position) + " of " + quoted(feature);
        if (!expect(item, YNode::Kind::Map, where, "a map with id, interval and labels"))
            return false;
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
        if (entries.count("interval"))
            d.bounds_ok = check_interval(entries.at("interval"), where, d);
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

    bool check_interval(const Entry& e, const std::string& where, ConceptDraft& d) {
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

    Bound bound(int item, const std::string& where, const char* which) {
        const YNode& v = node(item);
        const std::string what = where + ": " + which + " bound";
        Bound b;
        if (v.kind != YNode::Kind::Scalar) {
            p_.add(v.offset, what + " must be a number or .inf/-.inf, found " + kind_name(v.kind));
            return b;
        }
        if (v.tag != "?" && v.tag != "tag:yaml.org,2002:float" &&
            v.tag != "tag:yaml.org,2002:int") {
            p_.add(v.offset, what + " " + quoted(v.value) +
                                 " is written as text (quoted or tagged); write the number bare");
            return b;
        }
        const std::string& s = v.value;
        if (s == ".inf" || s == ".Inf" || s == ".INF" || s == "+.inf" || s == "+.Inf" ||
            s == "+.INF") {
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
            for (char& ch : lower)
                ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
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
            p_.add(v.offset, what + " " + quoted(s) + " is below the smallest normal double (2.2e-308)");
            return b;
        }
        b = {true, value, text};
        return b;
    }

    static std::string bound_text(double v, const std::string& text) {
        return text.empty() ? (v < 0 ? "-.inf" : ".inf") : text;
    }
    static std::string interval_text(const DictionaryConcept& c) {
        return "[" + bound_text(c.lower, c.lower_text) + ", " + bound_text(c.upper, c.upper_text) +
               ")";
    }

    void check_unique_ids(const std::vector<ConceptDraft>& drafts) {
        std::map<std::string, size_t> first;
        for (const auto& d : drafts) {
            if (d.concept_.id.empty()) continue;
            const auto [it, fresh] = first.emplace(d.concept_.id, d.id_offset);
            if (!fresh)
                p_.add(d.id_offset, "duplicate concept id " + quoted(d.concept_.id) +
                                        " (first at line " +
                                        std::to_string(p_.line_of(it->second)) +
                                        "); concept ids are unique in the dictionary");
        }
    }

    void check_overlaps(const std::vector<ConceptDraft>& drafts) {
        std::vector<const ConceptDraft*> ok;
        for (const auto& d : drafts)
            if (d.bounds_ok && d.concept_.feature >= 0) ok.push_back(&d);
        // file order: each pair is reported once, at the later of the two
        for (size_t j = 0; j < ok.size(); ++j)
            for (size_t i = 0; i < j; ++i) {
                const DictionaryConcept& a = ok[i]->concept_;
                const DictionaryConcept& b = ok[j]->concept_;
                if (a.feature != b.feature || !(a.lower < b.upper && b.lower < a.upper)) continue;
                p_.add(ok[j]->interval_offset,
                       "interval " + interval_text(b) + " of " + quoted(b.id) + " overlaps " +
                           interval_text(a) + " of " + quoted(a.id) + " (line " +
                           std::to_string(a.line) + "); intervals of one feature must be disjoint");
            }
    }

    /// "unknown feature 'x'" with the closest id when there is one; `where` says where it was
    /// found (" in facet 'outline'", or "" under `features`).
    static std::string unknown_feature(const std::string& id, const std::string& where) {
        const std::string guess = closest(id, feature_spellings());
        return "unknown feature " + quoted(id) + where +
               (guess.empty() ? " (the " + std::to_string(kNumFeatures) +
                                    " feature ids are listed in docs/features.md)"
                              : "; did you mean " + quoted(guess) + "?");
    }

    void check_relief(const Entry& e, const std::string& where, DictionaryConcept& c) {
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

    /// The `facets` section: a map from facet id to {labels, features}. Which facet each
    /// feature is in is recorded for finish_facets, which runs once the features are read.
    void check_facets(const Entry& e) {
        if (!expect(e, YNode::Kind::Map, "facets",
                    "a map from facet id to its labels and features"))
            return;
        const YNode& m = node(e.second);
        facets_read_ = !m.items.empty();  // an empty map is one problem, not one per feature
        if (m.items.empty())
            p_.add(m.offset,
                   "facets is empty: list at least one facet, or remove the key (then each "
                   "feature is its own facet)");
        for (size_t k = 0; k + 1 < m.items.size(); k += 2) {
            const YNode& key = node(m.items[k]);
            if (key.kind != YNode::Kind::Scalar) {
                p_.add(key.offset,
                       "a facet id must be a text, found " + std::string(kind_name(key.kind)));
                continue;
            }
            FacetDraft f;
            f.facet.id = key.value;
            const auto [line, column] = p_.places->at(key.offset);
            f.facet.line = line;
            f.facet.column = column;
            const std::string where = "facet " + quoted(key.value);
            if (!is_id(key.value))
                p_.add(key.offset, "facet id " + quoted(key.value) +
                                       " may hold only letters, digits, '-', '_' and '.'");
            const Entry value{m.items[k], m.items[k + 1]};
            if (!expect(value, YNode::Kind::Map, where, "a map with labels and features")) {
                facet_drafts_.push_back(std::move(f));
                continue;
            }
            const auto entries = map_entries(value.second, kFacetKeys, "in a facet");
            if (!entries.count("labels")) missing(value.second, where, "labels");
            if (!entries.count("features")) missing(value.second, where, "features");
            if (entries.count("labels"))
                texts_by_language(entries.at("labels"), where + ": labels", f.facet.labels, false,
                                  languages_ok_ ? &languages_ : nullptr, &f.label_offsets);
            if (entries.count("features")) check_facet_features(entries.at("features"), where, f);
            facet_drafts_.push_back(std::move(f));
        }
    }

    void check_facet_features(const Entry& e, const std::string& where, FacetDraft& f) {
        const char* none = " has no features: list the features whose concepts it groups";
        if (node(e.second).kind == YNode::Kind::Null) {
            p_.add(place(e), where + none);
            return;
        }
        if (!expect(e, YNode::Kind::Sequence, where + ": features",
                    "a list of feature ids ([contour_sphericity, perimeter2_area_ratio])"))
            return;
        const YNode& list = node(e.second);
        if (list.items.empty()) p_.add(list.offset, where + none);
        for (int item : list.items) {
            const YNode& v = node(item);
            if (v.kind != YNode::Kind::Scalar) {
                p_.add(v.offset, where + ": a feature id must be a text, found " +
                                     std::string(kind_name(v.kind)));
                continue;
            }
            const int feature = feature_index(v.value);
            if (feature < 0) {
                p_.add(v.offset, unknown_feature(v.value, " in " + where));
                continue;
            }
            const auto [it, fresh] =
                facet_of_feature_.emplace(feature, std::make_pair(facet_drafts_.size(), v.offset));
            if (!fresh) {
                const auto [other, other_offset] = it->second;
                const auto [line, column] = p_.places->at(other_offset);
                p_.add(v.offset,
                       other == facet_drafts_.size()
                           ? where + " lists " + quoted(v.value) + " twice (first at line " +
                                 std::to_string(line) + ", column " + std::to_string(column) + ")"
                           : "feature " + quoted(v.value) + " is in two facets: " + where +
                                 " here and " + quoted(facet_drafts_[other].facet.id) +
                                 " at line " + std::to_string(line) + ", column " +
                                 std::to_string(column) +
                                 "; a feature belongs to one facet, whose concepts exclude each "
                                 "other");
                continue;
            }
            f.facet.features.push_back(feature);
            f.feature_offsets.push_back(v.offset);
        }
    }

    /// With a `facets` section: every feature with concepts must be in a facet; a facet entry
    /// without concepts only earns a warning. Fills facets and feature_facet.
    void finish_facets(Dictionary& out) {
        out.declares_facets = true;
        out.feature_facet.assign(kNumFeatures, -1);
        std::vector<bool> has_concepts(kNumFeatures, false);
        for (const auto& c : out.concepts) has_concepts[c.feature] = true;
        check_unique_facet_labels();
        check_facet_concept_labels();
        for (size_t i = 0; i < facet_drafts_.size(); ++i) {
            const FacetDraft& f = facet_drafts_[i];
            for (size_t j = 0; j < f.facet.features.size(); ++j) {
                const int feature = f.facet.features[j];
                if (has_concepts[feature])
                    out.feature_facet[feature] = static_cast<int>(i);
                else
                    warn(f.feature_offsets[j],
                         "facet " + quoted(f.facet.id) + " lists " + quoted(kFeatureIds[feature]) +
                             ", which has no concepts: it adds nothing to the facet");
            }
            out.facets.push_back(f.facet);
        }
        if (!facets_read_) return;  // `facets` is not even a map: that is the problem to fix
        for (int feature = 0; feature < kNumFeatures; ++feature)
            if (has_concepts[feature] && !facet_of_feature_.count(feature))
                p_.add(feature_key_[feature],
                       "feature " + quoted(kFeatureIds[feature]) +
                           " has concepts but is in no facet: add it to the 'features' of one "
                           "facet (a texture gets at most one concept per facet)");
    }

    /// Without a `facets` section (a dictionary older than facets): each feature with concepts
    /// is its own facet, named by the feature id, and a warning says what that costs.
    void one_facet_per_feature(Dictionary& out) {
        out.declares_facets = false;
        out.feature_facet.assign(kNumFeatures, -1);
        for (const auto& c : out.concepts) {
            if (out.feature_facet[c.feature] >= 0) continue;
            DictionaryFacet f;
            f.id = kFeatureIds[c.feature];
            for (const auto& lang : out.languages) f.labels.emplace(lang, f.id);
            f.features.push_back(c.feature);
            const auto [line, column] = p_.places->at(feature_key_[c.feature]);
            f.line = line;
            f.column = column;
            out.feature_facet[c.feature] = static_cast<int>(out.facets.size());
            // The implicit facet is a top concept of the scheme too, labelled by the feature id.
            for (const auto& [lang, label] : f.labels) {
                const auto same = concept_labels_.find({lang, label_key(label)});
                if (same == concept_labels_.end()) continue;
                p_.add(same->second.offset,
                       concept_name(same->second.id) + ": label " + quoted(same->second.label) +
                           " in " + quoted(lang) +
                           " is also the label of the facet that a dictionary without 'facets' "
                           "makes of feature " +
                           quoted(f.id) +
                           "; change the label or declare the facets (a facet is a concept of "
                           "the scheme: the two could not be told apart)");
            }
            out.facets.push_back(std::move(f));
        }
        warnings.push_back(
            {1, 1,
             "no facets: each feature is its own facet, so a texture may get several concepts "
             "of one kind (e.g. 'flat' from one feature and 'curved' from another); group the "
             "features under 'facets' (dictionaries/README.md)"});
    }

    void warn(size_t offset, std::string message) {
        const auto [line, column] = p_.places->at(offset);
        warnings.push_back({line, column, std::move(message)});
    }

    /// Labels are compared without regard to ASCII case: "Flat region" and "flat region"
    /// cannot be told apart by a reader either.
    static std::string label_key(const std::string& label) {
        std::string key = label;
        for (char& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        return key;
    }

    std::string place_text(size_t offset) const {
        const auto [line, column] = p_.places->at(offset);
        return "line " + std::to_string(line) + ", column " + std::to_string(column);
    }

    /// Two concepts with one label in one language: a reader of the annotations could not
    /// tell them apart. Reported at the later label, naming the earlier one's place.
    void check_unique_labels(const std::vector<ConceptDraft>& drafts) {
        std::map<std::pair<std::string, std::string>, std::pair<const ConceptDraft*, size_t>> first;
        for (const auto& d : drafts)
            for (const auto& [lang, offset] : d.label_offsets) {
                const std::string& label = d.concept_.labels.at(lang);
                const auto [it, fresh] = first.emplace(std::make_pair(lang, label_key(label)),
                                                       std::make_pair(&d, offset));
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

    void check_unique_facet_labels() {
        std::map<std::pair<std::string, std::string>, std::pair<const FacetDraft*, size_t>> first;
        for (const auto& f : facet_drafts_)
            for (const auto& [lang, offset] : f.label_offsets) {
                const std::string& label = f.facet.labels.at(lang);
                const auto [it, fresh] = first.emplace(std::make_pair(lang, label_key(label)),
                                                       std::make_pair(&f, offset));
                if (fresh) continue;
                p_.add(offset, "facet " + quoted(f.facet.id) + ": label " + quoted(label) + " in " +
                                   quoted(lang) + " is also the label of facet " +
                                   quoted(it->second.first->facet.id) + " at " +
                                   place_text(it->second.second) +
                                   "; two facets with one label cannot be told apart");
            }
    }

    static std::string concept_name(const std::string& id) {
        return id.empty() ? std::string("a concept") : "concept " + quoted(id);
    }

    /// A facet is a top concept of the SKOS scheme (skos:broader of its concepts), so its
    /// label must differ from every concept's in the same language. Reported at the facet's
    /// label, naming the concept's place.
    void check_facet_concept_labels() {
        for (const auto& f : facet_drafts_)
            for (const auto& [lang, offset] : f.label_offsets) {
                const std::string& label = f.facet.labels.at(lang);
                const auto same = concept_labels_.find({lang, label_key(label)});
                if (same == concept_labels_.end()) continue;
                p_.add(offset, "facet " + quoted(f.facet.id) + ": label " + quoted(label) + " in " +
                                   quoted(lang) + " is also the label of " +
                                   concept_name(same->second.id) + " at " +
                                   place_text(same->second.offset) +
                                   "; a facet is a concept of the scheme too: the two could not "
                                   "be told apart");
            }
    }

    std::string_view text_;
    const std::vector<YNode>& n_;
    Problems& p_;
    std::set<std::string> guessed_;       // keys suggested for the typos of the last map read
    std::vector<std::string> languages_;  // required languages, once the scheme is read
    bool languages_ok_ = false;
    std::vector<size_t> feature_key_ =
        std::vector<size_t>(kNumFeatures, std::string::npos);    // place of each feature's key
    std::vector<FacetDraft> facet_drafts_;                       // in the YAML's order
    std::map<int, std::pair<size_t, size_t>> facet_of_feature_;  // feature -> facet, place
    bool facets_read_ = false;  // `facets` is a map, so a feature outside it is a problem
    // (language, label_key) -> concept id and place of its label, the first of each
    struct ConceptLabel {
        std::string id;     // of the concept
        size_t offset = 0;  // place of the label text
        std::string label;  // as written
    };
    std::map<std::pair<std::string, std::string>, ConceptLabel> concept_labels_;
};

struct Analysis {
    Dictionary dictionary;
    std::vector<DictionaryProblem> problems;
};

Analysis analyse(std::string_view text) {
    Analysis a;
    const Places places(text);
    Problems problems{&places, {}};
    const YamlTree tree = read_yaml_tree(text, problems);
    Checker checker(text, tree.nodes, problems);
    checker.check_duplicate_keys();
    // The structure is checked only on a tree that is what the curator wrote: after a syntax
    // error or a runaway quote, missing keys would be consequences, not problems of their own.
    if (tree.readable) {
        if (tree.roots.empty()) {
            problems.add(0,
                         "empty dictionary: expected a map with the keys 'scheme' and 'features'");
        } else {
            checker.check_document(tree.roots[0], a.dictionary);
        }
    }
    a.problems = std::move(problems.list);
    a.dictionary.warnings = std::move(checker.warnings);
    std::stable_sort(a.dictionary.warnings.begin(), a.dictionary.warnings.end(),
                     [](const DictionaryProblem& x, const DictionaryProblem& y) {
                         return x.line != y.line ? x.line < y.line : x.column < y.column;
                     });
    std::stable_sort(a.problems.begin(), a.problems.end(),
                     [](const DictionaryProblem& x, const DictionaryProblem& y) {
                         return x.line != y.line ? x.line < y.line : x.column < y.column;
                     });
    return a;
}

}  // namespace

std::vector<DictionaryProblem> check_dictionary(std::string_view yaml_text) {
    return analyse(yaml_text).problems;
}

Dictionary parse_dictionary(std::string_view yaml_text, const std::string& name) {
    Analysis a = analyse(yaml_text);
    if (!a.problems.empty()) {
        const DictionaryProblem& first = a.problems.front();
        std::string what = "dictionary: " + first.message;
        if (a.problems.size() > 1)
            what += " (and " + std::to_string(a.problems.size() - 1) + " more problem" +
                    (a.problems.size() > 2 ? "s" : "") + "; 'geotex dict check' lists them all)";
        throw ParseError(what, name, first.line, first.column);
    }
    a.dictionary.sha256 = sha256_hex(yaml_text);
    a.dictionary.source_name = name;
    return std::move(a.dictionary);
}

}  // namespace geotex
