// The facets of a dictionary: their features (each in one facet), labels, and one facet
// per feature for a dictionary that declares none.

#include "annotation/detail/dictionary_checker.hpp"

namespace geotex::dictionary_detail {

void Checker::check_facets(const Entry& e) {
    if (!expect(e, YNode::Kind::Map, "facets", "a map from facet id to its labels and features"))
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

void Checker::check_facet_features(const Entry& e, const std::string& where, FacetDraft& f) {
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
                             " here and " + quoted(facet_drafts_[other].facet.id) + " at line " +
                             std::to_string(line) + ", column " + std::to_string(column) +
                             "; a feature belongs to one facet, whose concepts exclude each "
                             "other");
            continue;
        }
        f.facet.features.push_back(feature);
        f.feature_offsets.push_back(v.offset);
    }
}

void Checker::finish_facets(Dictionary& out) {
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

void Checker::one_facet_per_feature(Dictionary& out) {
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

void Checker::check_unique_facet_labels() {
    std::map<std::pair<std::string, std::string>, std::pair<const FacetDraft*, size_t>> first;
    for (const auto& f : facet_drafts_)
        for (const auto& [lang, offset] : f.label_offsets) {
            const std::string& label = f.facet.labels.at(lang);
            const auto [it, fresh] =
                first.emplace(std::make_pair(lang, label_key(label)), std::make_pair(&f, offset));
            if (fresh) continue;
            p_.add(offset, "facet " + quoted(f.facet.id) + ": label " + quoted(label) + " in " +
                               quoted(lang) + " is also the label of facet " +
                               quoted(it->second.first->facet.id) + " at " +
                               place_text(it->second.second) +
                               "; two facets with one label cannot be told apart");
        }
}

void Checker::check_facet_concept_labels() {
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

}  // namespace geotex::dictionary_detail
