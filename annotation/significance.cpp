#include "annotation/significance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geometry/errors.hpp"
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

}  // namespace

std::vector<TextureDescription> describe_textures(const Eigen::MatrixXd& features,
                                                  const std::vector<int>& texel_texture,
                                                  int num_textures, const Dictionary& dictionary,
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
    if (params.num_concepts < 0)
        throw InvalidInput(stage + "num_concepts is " + std::to_string(params.num_concepts) +
                           "; it must be >= 0");

    const int num_texels = static_cast<int>(texel_texture.size());
    std::vector<std::vector<int>> members(static_cast<size_t>(num_textures));
    for (int t = 0; t < num_texels; ++t) {
        const int label = texel_texture[static_cast<size_t>(t)];
        if (label < 0 || label >= num_textures)
            throw InvalidInput(stage + "texel " + std::to_string(t) + " has texture " +
                               std::to_string(label) + ", outside [0, " +
                               std::to_string(num_textures) +
                               "); background texels (-1) must be left out of the table");
        members[static_cast<size_t>(label)].push_back(t);
    }
    int num_empty = 0, first_empty = -1;
    for (int k = 0; k < num_textures; ++k)
        if (members[static_cast<size_t>(k)].empty()) {
            if (num_empty++ == 0) first_empty = k;
        }
    if (num_empty > 0)
        throw InvalidInput(stage + std::to_string(num_empty) + " of " +
                           std::to_string(num_textures) +
                           " textures have no texel (first: " + std::to_string(first_empty) +
                           "); number the textures 0..num_textures-1 without gaps");
    for (int t = 0; t < num_texels; ++t)
        for (int i = 0; i < kNumFeatures; ++i)
            if (!std::isfinite(features(t, i)))
                throw InvalidInput(stage + "texel " + std::to_string(t) + " has a non-finite " +
                                   kFeatureIds[static_cast<size_t>(i)] +
                                   "; the feature table must be finite");

    // sigma over all texels, and whether the feature is constant (S undefined)
    std::vector<int> all(static_cast<size_t>(num_texels));
    std::iota(all.begin(), all.end(), 0);
    std::vector<double> sigma_all(kNumFeatures, 0);
    std::vector<bool> constant(kNumFeatures, true);
    if (num_texels > 0)
        for (int i = 0; i < kNumFeatures; ++i) {
            sigma_all[i] = moments(features, all, i).sigma;
            const double magnitude = features.col(i).cwiseAbs().maxCoeff();
            constant[i] = !(sigma_all[i] > kConstantRelTol * magnitude);
        }

    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<TextureDescription> out;
    out.reserve(static_cast<size_t>(num_textures));
    for (int k = 0; k < num_textures; ++k) {
        const std::vector<int>& rows = members[static_cast<size_t>(k)];
        TextureDescription d;
        d.texture = k;
        d.num_texels = static_cast<int>(rows.size());

        std::vector<FeatureScore> scores(kNumFeatures);
        for (int i = 0; i < kNumFeatures; ++i) {
            const Moments m = moments(features, rows, i);
            FeatureScore& s = scores[static_cast<size_t>(i)];
            s.feature = i;
            s.value = m.mean;
            s.significance = constant[i] ? nan : m.sigma / sigma_all[i];
            s.concept_ptr = dictionary.find(i, m.mean);
        }
        // defined S ascending, ties by column order; the undefined ones last, in column order
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
            if (std::isnan(s.significance)) continue;
            s.rank = ++rank;
            ++num_defined;
            if (s.concept_ptr && static_cast<int>(d.chosen.size()) < params.num_concepts) {
                s.chosen = true;
                d.chosen.push_back(static_cast<int>(j));
            }
        }
        d.features = std::move(scores);

        std::vector<std::string> notes;
        if (num_defined == 0) {
            notes.push_back(
                "every feature is constant over all texels, so no feature is significant (S is "
                "undefined) and no concept is chosen");
        } else if (d.num_texels == 1) {
            notes.push_back(
                "one texel: its spread is 0 for every feature, so every defined S is 0 and the "
                "features are ranked in column order");
        } else if (d.num_texels == num_texels) {
            notes.push_back(
                "the texture holds every texel: S is 1 for every defined feature, so the "
                "features are ranked in column order");
        }
        if (num_defined > 0 && static_cast<int>(d.chosen.size()) < params.num_concepts)
            notes.push_back("only " + std::to_string(d.chosen.size()) + " of " +
                            std::to_string(params.num_concepts) +
                            " concepts: no other feature has both a defined S and a value in an "
                            "interval of the dictionary");
        for (const auto& n : notes) d.note += (d.note.empty() ? "" : "; ") + n;
        out.push_back(std::move(d));
    }
    return out;
}

}  // namespace geotex
