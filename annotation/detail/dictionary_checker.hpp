#pragma once
// The dictionary checker (private to annotation/): one pass over the YAML tree that reports
// every problem at once with its place. Its work is split by file: dictionary_checker.cpp
// walks the document and reads values (keys, texts, IRIs), dictionary_scheme.cpp the scheme,
// dictionary_concepts.cpp the features, their concepts and intervals, dictionary_facets.cpp
// the facets; annotation/dictionary.cpp runs it.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "annotation/detail/dictionary_text.hpp"
#include "annotation/dictionary.hpp"
#include "annotation/yaml_tree.hpp"
#include "common/detail/text.hpp"
#include "common/errors.hpp"
#include "geometry/feature_table.hpp"

namespace geotex::dictionary_detail {

// A private header of the checker's files: these names are theirs to use unqualified.
using namespace yaml_detail;
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

inline const std::vector<std::string> kTopKeys = {"scheme", "facets", "features"};
inline const std::vector<std::string> kSchemeKeys = {
    "id", "version", "namespace", "title", "languages", "creator", "license", "modified"};
inline const std::vector<std::string> kRequiredSchemeKeys = {"id", "version", "namespace", "title",
                                                             "languages"};
inline const std::vector<std::string> kFacetKeys = {"labels", "features"};
inline const std::vector<std::string> kConceptKeys = {
    "id", "interval", "labels", "definition", "source", "relief", "exactMatch", "closeMatch"};
inline const std::vector<std::pair<std::string, Relief>> kReliefs = {
    {"raised", Relief::Raised}, {"engraved", Relief::Engraved}};

/// Other spellings curators may use for a feature (the paper's names), to suggest the id.
inline const std::vector<std::pair<std::string, std::string>>& feature_spellings() {
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

    void check_duplicate_keys();

    void check_document(int root, Dictionary& out);

    /// What loads but deserves a look, sorted by place.
    std::vector<DictionaryProblem> warnings;

  private:
    const YNode& node(int i) const { return n_[static_cast<size_t>(i)]; }

    /// Reports a required key that is absent, unless an unknown key of the same map was taken
    /// for a typo of it (that problem already says "did you mean").
    void missing(int map, const std::string& where, const std::string& key);

    /// Place to report a problem about the value of an entry: the value, or its key when the
    /// value is empty (an empty value has no place of its own).
    size_t place(const Entry& e) const;

    bool expect(int value, YNode::Kind kind, const std::string& what, const std::string& expected,
                size_t where = std::string::npos);
    bool expect(const Entry& e, YNode::Kind kind, const std::string& what,
                const std::string& expected);

    /// The entries of a map by key; unknown keys are reported with the closest known one.
    std::map<std::string, Entry> map_entries(int map, const std::vector<std::string>& known,
                                             const std::string& where);

    /// A text value (one line unless `multi_line`); reports and returns false otherwise.
    bool text(const Entry& e, const std::string& what, std::string& out, bool multi_line = false);

    /// A map language tag -> text; checks the tags and, when `required` is given, that every
    /// required language is there.
    void texts_by_language(const Entry& e, const std::string& what,
                           std::map<std::string, std::string>& out, bool multi_line,
                           const std::vector<std::string>* required,
                           std::map<std::string, size_t>* offsets = nullptr);

    void check_scheme(const Entry& e, Dictionary& out);

    /// An IRI, or a list of them (`expected` says so; "" when only one is allowed and the
    /// caller checked that): each absolute as RDF needs it, none twice.
    void iris(const Entry& e, const std::string& what, std::vector<std::string>& out,
              const std::string& expected, bool web_only = false);

    /// The date of this version, as dcterms:modified (an xsd:date) says it. Unquoted, YAML 1.1
    /// would read it as a timestamp; yaml-cpp keeps the text, which is all we need.
    void check_modified(const Entry& e, Dictionary& out);

    void check_languages(const Entry& e, Dictionary& out);

    void check_features(const Entry& e, Dictionary& out);

    bool check_concept(int item, const std::string& feature, int position, ConceptDraft& d);

    bool check_interval(const Entry& e, const std::string& where, ConceptDraft& d);

    Bound bound(int item, const std::string& where, const char* which);

    static std::string bound_text(double v, const std::string& text);
    static std::string interval_text(const DictionaryConcept& c);

    void check_unique_ids(const std::vector<ConceptDraft>& drafts);

    void check_overlaps(const std::vector<ConceptDraft>& drafts);

    /// "unknown feature 'x'" with the closest id when there is one; `where` says where it was
    /// found (" in facet 'outline'", or "" under `features`).
    static std::string unknown_feature(const std::string& id, const std::string& where);

    void check_relief(const Entry& e, const std::string& where, DictionaryConcept& c);

    /// The `facets` section: a map from facet id to {labels, features}. Which facet each
    /// feature is in is recorded for finish_facets, which runs once the features are read.
    void check_facets(const Entry& e);

    void check_facet_features(const Entry& e, const std::string& where, FacetDraft& f);

    /// With a `facets` section: every feature with concepts must be in a facet; a facet entry
    /// without concepts only earns a warning. Fills facets and feature_facet.
    void finish_facets(Dictionary& out);

    /// Without a `facets` section (a dictionary older than facets): each feature with concepts
    /// is its own facet, named by the feature id, and a warning says what that costs.
    void one_facet_per_feature(Dictionary& out);

    void warn(size_t offset, std::string message);

    /// Labels are compared without regard to ASCII case: "Flat region" and "flat region"
    /// cannot be told apart by a reader either.
    static std::string label_key(const std::string& label);

    std::string place_text(size_t offset) const;

    /// Two concepts with one label in one language: a reader of the annotations could not
    /// tell them apart. Reported at the later label, naming the earlier one's place.
    void check_unique_labels(const std::vector<ConceptDraft>& drafts);

    void check_unique_facet_labels();

    static std::string concept_name(const std::string& id);

    /// A facet is a top concept of the SKOS scheme (skos:broader of its concepts), so its
    /// label must differ from every concept's in the same language. Reported at the facet's
    /// label, naming the concept's place.
    void check_facet_concept_labels();

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

}  // namespace geotex::dictionary_detail
