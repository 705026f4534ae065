#include "annotation/significance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/errors.hpp"
#include "geometry/feature_table.hpp"

namespace geotex {

namespace {

/// A feature whose population standard deviation over all texels is at most this fraction
/// of its largest magnitude is taken as constant (S undefined). Features vary over many
/// orders of magnitude (PCA ratios ~1e-3, Gaussian curvature ~1e3), so only a relative test
/// is meaningful. Mesh coordinates usually come as float32 (relative precision 6e-8), so a
/// spread below 1e-8 of the feature's magnitude cannot come from the geometry; the rounding
/// of our own sums stays below it even over 10^7 terms (n * 2^-53 ~ 1e-9).
constexpr double kConstantRelTol = 1e-8;

struct Moments {
    double mean = 0;
    double sigma = 0;  // population standard deviation
};

/// Mean and population standard deviation of features(rows, col). The values are shifted by
/// the first one before summing, so equal values give exactly sigma = 0 and the mean is that
/// value, and a large common offset does not cancel the digits of a small spread.
Moments moments(const Eigen::MatrixXd& features, const std::vector<int>& rows, int col) {
    const double origin = features(rows.front(), col);
    double sum = 0;
    for (int r : rows) sum += features(r, col) - origin;
    const double n = static_cast<double>(rows.size());
    const double shift = sum / n;
    double squares = 0;
    for (int r : rows) {
        const double d = features(r, col) - origin - shift;
        squares += d * d;
    }
    return {origin + shift, std::sqrt(squares / n)};
}

/// The facets as lists of feature columns in the order of preference. A dictionary built in
/// code without facets (feature_facet empty) has each feature as its own facet.
std::vector<std::vector<int>> facet_features(const Dictionary& dictionary) {
    std::vector<std::vector<int>> out;
    if (!dictionary.feature_facet.empty()) {
        for (const auto& f : dictionary.facets) out.push_back(f.features);
        return out;
    }
    for (int i = 0; i < kNumFeatures; ++i) out.push_back({i});
    return out;
}

/// Every texel of every texture, one sample of them: rows[k] are the rows of texture k in
/// the feature table (with repetitions in a bootstrap resample).
using Sample = std::vector<std::vector<int>>;

/// What the rule says about one texture on one sample.
struct Evaluation {
    std::vector<FeatureScore> scores;  ///< kNumFeatures, in column order
    std::vector<int> pick;             ///< per facet: the column picked, or -1
};

/// The choice rule (docs/words.md) and what it needs besides one sample of texels.
struct ChoiceRule {
    const Eigen::MatrixXd& features;    ///< #texels by kNumFeatures
    const std::vector<bool>& constant;  ///< per feature: S undefined (same over all texels)
    bool single_texture = false;        ///< nothing to set a texture apart from
    const Dictionary& dictionary;
    const std::vector<std::vector<int>>& facets;  ///< feature columns, in order of preference
    const DescriptionParams& params;

    /// Per facet, the first feature in the dictionary's order with a defined S (S <=
    /// max_significance when that test is on and there is more than one texture), whose mean
    /// over `rows` lies in a concept allowed for the texture's relief, and whose concept holds
    /// for at least min_agreement of the rows. `sigma_all` is sigma over all texels of the
    /// sample.
    Evaluation evaluate(const std::vector<int>& rows, const std::vector<double>& sigma_all,
                        DetailOrientation orientation) const;
};

Evaluation ChoiceRule::evaluate(const std::vector<int>& rows, const std::vector<double>& sigma_all,
                                DetailOrientation orientation) const {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Evaluation e;
    e.scores.resize(kNumFeatures);
    for (int i = 0; i < kNumFeatures; ++i) {
        const Moments m = moments(features, rows, i);
        FeatureScore& s = e.scores[static_cast<size_t>(i)];
        s.feature = i;
        s.value = m.mean;
        // A resample may hold one value of a feature that varies over the texels: then the
        // texture is as tight as the whole, S = 0 (its own sigma is 0 too).
        const double whole = sigma_all[static_cast<size_t>(i)];
        s.significance = constant[static_cast<size_t>(i)] ? nan : whole > 0 ? m.sigma / whole : 0.0;
        s.concept_ptr = dictionary.find(i, m.mean);
        if (s.concept_ptr) {
            int inside = 0;
            for (int r : rows) {
                const double v = features(r, i);
                inside += s.concept_ptr->lower <= v && v < s.concept_ptr->upper;
            }
            s.agreement = static_cast<double>(inside) / static_cast<double>(rows.size());
        }
    }
    e.pick.assign(facets.size(), -1);
    for (size_t f = 0; f < facets.size(); ++f)
        for (int i : facets[f]) {
            const FeatureScore& s = e.scores[static_cast<size_t>(i)];
            if (std::isnan(s.significance) || !s.concept_ptr) continue;
            if (params.max_significance > 0 && !single_texture &&
                !(s.significance <= params.max_significance))
                continue;
            if (!relief_allows(s.concept_ptr->relief, orientation)) continue;
            if (!(s.agreement >= params.min_agreement)) continue;
            e.pick[f] = i;
            break;
        }
    return e;
}

/// sigma over the union of the sample's rows, per feature.
std::vector<double> sigma_over_all(const Eigen::MatrixXd& features, const Sample& sample) {
    std::vector<int> all;
    for (const auto& rows : sample) all.insert(all.end(), rows.begin(), rows.end());
    std::vector<double> sigma(kNumFeatures, 0);
    if (all.empty()) return sigma;
    for (int i = 0; i < kNumFeatures; ++i)
        sigma[static_cast<size_t>(i)] = moments(features, all, i).sigma;
    return sigma;
}

/// SplitMix64 (Steele, Lea & Flood 2014): a counter-based generator, so that the resample of
/// (texture, replicate) does not depend on the order in which other resamples were drawn.
/// Written here because std's engines are sequential and <random>'s distributions are not
/// specified bit for bit across standard libraries.
std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/// Row `j` of a resample of `rows`: uniform over rows (Lemire's multiply-shift; the bias of
/// at most n / 2^64 is far below what 200 resamples can see).
int draw(const std::vector<int>& rows, std::uint64_t key) {
    const unsigned __int128 wide = static_cast<unsigned __int128>(splitmix64(key)) * rows.size();
    return rows[static_cast<size_t>(wide >> 64)];
}

void check_inputs(const Eigen::MatrixXd& features, const std::vector<int>& texel_texture,
                  int num_textures, const std::vector<DetailOrientation>& texture_orientation,
                  const DescriptionParams& params) {
    const std::string stage = "describe_textures: ";
    if (features.cols() != kNumFeatures)
        throw InvalidInput(stage + "the feature table has " + std::to_string(features.cols()) +
                           " columns; expected " + std::to_string(kNumFeatures) +
                           " (one per id of kFeatureIds, in that order)");
    if (static_cast<size_t>(features.rows()) != texel_texture.size())
        throw InvalidInput(stage + "the feature table has " + std::to_string(features.rows()) +
                           " rows but texel_texture has " + std::to_string(texel_texture.size()) +
                           " labels; pass one label per texel");
    if (num_textures < 0)
        throw InvalidInput(stage + "num_textures is " + std::to_string(num_textures) +
                           "; it must be >= 0");
    if (!texture_orientation.empty() &&
        texture_orientation.size() != static_cast<size_t>(num_textures))
        throw InvalidInput(stage + "texture_orientation has " +
                           std::to_string(texture_orientation.size()) + " entries for " +
                           std::to_string(num_textures) +
                           " textures; pass one per texture, or none (all raised)");
    if (params.max_concepts < 0)
        throw InvalidInput(stage + "max_concepts is " + std::to_string(params.max_concepts) +
                           "; it must be >= 0 (0: no cap)");
    if (!(params.max_significance >= 0) || !std::isfinite(params.max_significance))
        throw InvalidInput(stage + "max_significance is " +
                           std::to_string(params.max_significance) +
                           "; it must be >= 0 and finite (0: no test)");
    if (!(params.min_agreement > 0 && params.min_agreement <= 1))
        throw InvalidInput(stage + "min_agreement is " + std::to_string(params.min_agreement) +
                           "; it must be in (0, 1]");
    if (!(params.min_stability >= 0 && params.min_stability <= 1))
        throw InvalidInput(stage + "min_stability is " + std::to_string(params.min_stability) +
                           "; it must be in [0, 1]");
    if (params.num_resamples < 0)
        throw InvalidInput(stage + "num_resamples is " + std::to_string(params.num_resamples) +
                           "; it must be >= 0 (0: every picked concept counts as stable)");
    for (Eigen::Index t = 0; t < features.rows(); ++t)
        for (int i = 0; i < kNumFeatures; ++i)
            if (!std::isfinite(features(t, i)))
                throw InvalidInput(stage + "texel " + std::to_string(t) + " has a non-finite " +
                                   kFeatureIds[static_cast<size_t>(i)] +
                                   "; the feature table must be finite");
}

/// The rows of each texture, sorted by their feature values: every later sum and draw runs
/// in this order, so the description does not depend on the order of the texels.
Sample canonical_members(const Eigen::MatrixXd& features, const std::vector<int>& texel_texture,
                         int num_textures) {
    const std::string stage = "describe_textures: ";
    Sample members(static_cast<size_t>(num_textures));
    for (size_t t = 0; t < texel_texture.size(); ++t) {
        const int label = texel_texture[t];
        if (label < 0 || label >= num_textures)
            throw InvalidInput(stage + "texel " + std::to_string(t) + " has texture " +
                               std::to_string(label) + ", outside [0, " +
                               std::to_string(num_textures) +
                               "); background texels (-1) must be left out of the table");
        members[static_cast<size_t>(label)].push_back(static_cast<int>(t));
    }
    int num_empty = 0, first_empty = -1;
    for (int k = 0; k < num_textures; ++k)
        if (members[static_cast<size_t>(k)].empty() && num_empty++ == 0) first_empty = k;
    if (num_empty > 0)
        throw InvalidInput(stage + std::to_string(num_empty) + " of " +
                           std::to_string(num_textures) +
                           " textures have no texel (first: " + std::to_string(first_empty) +
                           "); number the textures 0..num_textures-1 without gaps");
    const auto by_values = [&](int a, int b) {
        for (int i = 0; i < kNumFeatures; ++i)
            if (features(a, i) != features(b, i)) return features(a, i) < features(b, i);
        return false;  // equal rows: their order changes no sum
    };
    for (auto& rows : members) std::stable_sort(rows.begin(), rows.end(), by_values);
    return members;
}

std::string notes_for(const TextureDescription& d, int num_defined, bool single_texture,
                      const DescriptionParams& params) {
    std::vector<std::string> notes;
    if (num_defined == 0) {
        notes.push_back(
            "every feature is constant over all texels, so no feature is significant (S is "
            "undefined) and no concept is chosen");
    } else if (d.num_texels == 1 && !single_texture) {
        notes.push_back(
            "one texel: its spread is 0 for every feature, so every defined S is 0; its words "
            "are those of its own values");
    } else if (single_texture) {
        notes.push_back(
            "the texture holds every texel: S is 1 for every defined feature and sets nothing "
            "apart, so the concepts are those that hold for most of its texels");
    }
    if (!d.withheld.empty())
        notes.push_back(std::to_string(d.withheld.size()) +
                        " concept(s) withheld: chosen on the texels, but in fewer than " +
                        std::to_string(static_cast<int>(std::lround(params.min_stability * 100))) +
                        "% of the resamples of the texels, or beyond max_concepts");
    std::string out;
    for (const auto& n : notes) out += (out.empty() ? "" : "; ") + n;
    return out;
}

/// Whether each feature is constant over all texels (S undefined). Decided once, on the
/// texels themselves: a resample of a nearly constant feature must not make S defined in
/// some replicates only.
std::vector<bool> constant_features(const Eigen::MatrixXd& features,
                                    const std::vector<double>& sigma_all) {
    std::vector<bool> constant(kNumFeatures, true);
    if (features.rows() == 0) return constant;
    for (int i = 0; i < kNumFeatures; ++i) {
        const double magnitude = features.col(i).cwiseAbs().maxCoeff();
        constant[static_cast<size_t>(i)] =
            !(sigma_all[static_cast<size_t>(i)] > kConstantRelTol * magnitude);
    }
    return constant;
}

/// Bootstrap: each texture's texels resampled with replacement, S against the union of the
/// resamples, the rule run again. Returns, per texture and facet, how many resamples pick the
/// concept that `full` (the rule on the texels themselves) picked.
std::vector<std::vector<int>> resampled_agreement(
    const ChoiceRule& rule, const Sample& members, const std::vector<Evaluation>& full,
    const std::vector<DetailOrientation>& orientation) {
    const size_t num_textures = members.size();
    std::vector<std::vector<int>> agree(num_textures, std::vector<int>(rule.facets.size(), 0));
    Sample resample(num_textures);
    for (int b = 0; b < rule.params.num_resamples; ++b) {
        for (size_t k = 0; k < num_textures; ++k) {
            const auto& rows = members[k];
            auto& out = resample[k];
            out.resize(rows.size());
            const std::uint64_t key =
                splitmix64(rule.params.seed ^ splitmix64(static_cast<std::uint64_t>(k))) ^
                (static_cast<std::uint64_t>(b) << 32);
            for (size_t j = 0; j < rows.size(); ++j) out[j] = draw(rows, splitmix64(key + j));
        }
        const std::vector<double> sigma = sigma_over_all(rule.features, resample);
        for (size_t k = 0; k < num_textures; ++k) {
            const Evaluation e = rule.evaluate(resample[k], sigma, orientation[k]);
            for (size_t f = 0; f < rule.facets.size(); ++f) {
                const int i = full[k].pick[f];
                if (i >= 0 && e.pick[f] == i &&
                    e.scores[static_cast<size_t>(i)].concept_ptr ==
                        full[k].scores[static_cast<size_t>(i)].concept_ptr)
                    ++agree[k][f];
            }
        }
    }
    return agree;
}

/// Marks what the rule picked for one texture as chosen (stable, within max_concepts, the
/// most significant facets first) or withheld, and sets each score's stability and facet.
void settle_picks(Evaluation& e, const std::vector<int>& agree, const std::vector<int>& facet_of,
                  const DescriptionParams& params) {
    std::vector<int> picked;
    for (size_t f = 0; f < e.pick.size(); ++f) {
        const int i = e.pick[f];
        if (i < 0) continue;
        e.scores[static_cast<size_t>(i)].stability =
            params.num_resamples == 0 ? 1.0 : static_cast<double>(agree[f]) / params.num_resamples;
        picked.push_back(i);
    }
    for (int i = 0; i < kNumFeatures; ++i)
        e.scores[static_cast<size_t>(i)].facet = facet_of[static_cast<size_t>(i)];
    std::stable_sort(picked.begin(), picked.end(), [&](int a, int b) {
        return e.scores[static_cast<size_t>(a)].significance <
               e.scores[static_cast<size_t>(b)].significance;
    });
    int asserted = 0;
    for (int i : picked) {
        FeatureScore& s = e.scores[static_cast<size_t>(i)];
        const bool within_cap = params.max_concepts == 0 || asserted < params.max_concepts;
        if (s.stability >= params.min_stability && within_cap) {
            s.chosen = true;
            ++asserted;
        } else {
            s.withheld = true;
        }
    }
}

/// The description of texture k from its settled scores: features ranked by S (defined S
/// ascending, ties by column order; the undefined ones last, in column order).
TextureDescription ranked_description(int k, int num_texels, DetailOrientation orientation,
                                      std::vector<FeatureScore> scores, bool single_texture,
                                      const DescriptionParams& params) {
    TextureDescription d;
    d.texture = k;
    d.num_texels = num_texels;
    d.orientation = orientation;
    std::stable_sort(scores.begin(), scores.end(),
                     [](const FeatureScore& a, const FeatureScore& b) {
                         const bool a_nan = std::isnan(a.significance);
                         const bool b_nan = std::isnan(b.significance);
                         if (a_nan || b_nan) return !a_nan && b_nan;
                         return a.significance < b.significance;
                     });
    int rank = 0, num_defined = 0;
    for (size_t j = 0; j < scores.size(); ++j) {
        FeatureScore& s = scores[j];
        if (!s.chosen && !s.withheld) s.stability = 0;
        if (s.chosen) d.chosen.push_back(static_cast<int>(j));
        if (s.withheld) d.withheld.push_back(static_cast<int>(j));
        if (std::isnan(s.significance)) continue;
        s.rank = ++rank;
        ++num_defined;
    }
    d.features = std::move(scores);
    d.note = notes_for(d, num_defined, single_texture, params);
    return d;
}

}  // namespace

bool relief_allows(Relief relief, DetailOrientation orientation) {
    return relief == Relief::Any ||
           (relief == Relief::Raised) == (orientation == DetailOrientation::Positive);
}

std::vector<TextureDescription> describe_textures(
    const Eigen::MatrixXd& features, const std::vector<int>& texel_texture, int num_textures,
    const std::vector<DetailOrientation>& texture_orientation, const Dictionary& dictionary,
    const DescriptionParams& params) {
    check_inputs(features, texel_texture, num_textures, texture_orientation, params);
    const Sample members = canonical_members(features, texel_texture, num_textures);
    const std::vector<DetailOrientation> orientation =
        texture_orientation.empty()
            ? std::vector<DetailOrientation>(static_cast<size_t>(num_textures),
                                             DetailOrientation::Positive)
            : texture_orientation;

    const auto facets = facet_features(dictionary);
    std::vector<int> facet_of(kNumFeatures, -1);  // feature column -> index into facets
    for (size_t f = 0; f < facets.size(); ++f)
        for (int i : facets[f]) facet_of[static_cast<size_t>(i)] = static_cast<int>(f);
    if (dictionary.feature_facet.empty())  // each feature its own facet: only those with concepts
        for (int i = 0; i < kNumFeatures; ++i)
            if (std::none_of(dictionary.concepts.begin(), dictionary.concepts.end(),
                             [i](const DictionaryConcept& c) { return c.feature == i; }))
                facet_of[static_cast<size_t>(i)] = -1;

    const std::vector<double> sigma_all = sigma_over_all(features, members);
    const std::vector<bool> constant = constant_features(features, sigma_all);
    const ChoiceRule rule{features, constant, num_textures == 1, dictionary, facets, params};

    std::vector<Evaluation> full;  // the rule on the texels themselves
    for (int k = 0; k < num_textures; ++k)
        full.push_back(rule.evaluate(members[static_cast<size_t>(k)], sigma_all,
                                     orientation[static_cast<size_t>(k)]));
    const auto agree = resampled_agreement(rule, members, full, orientation);

    std::vector<TextureDescription> out;
    out.reserve(static_cast<size_t>(num_textures));
    for (int k = 0; k < num_textures; ++k) {
        Evaluation& e = full[static_cast<size_t>(k)];
        settle_picks(e, agree[static_cast<size_t>(k)], facet_of, params);
        out.push_back(ranked_description(
            k, static_cast<int>(members[static_cast<size_t>(k)].size()),
            orientation[static_cast<size_t>(k)], std::move(e.scores), rule.single_texture, params));
    }
    return out;
}

}  // namespace geotex
