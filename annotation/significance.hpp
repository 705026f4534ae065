#pragma once
/// Significance of the features for each texture and the choice of the concepts that
/// describe it (paper §4.3).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"

namespace geotex {

struct DescriptionParams {
    int num_concepts = 5;  ///< n: concepts chosen per texture (paper: 5)
};

/// One feature of one texture.
struct FeatureScore {
    int feature = -1;          ///< column in kFeatureIds
    double value = 0;          ///< V(i,T): mean of the feature over the texture's texels
    double significance = 0;   ///< S(i,T) = sigma over T / sigma over all texels (population
                               ///< std); NaN when the feature is constant over all texels
    int rank = 0;              ///< 1 = most significant; 0 when S is NaN
    const DictionaryConcept* concept_ptr = nullptr;  ///< interval holding the value, if any
    bool chosen = false;       ///< among the n concepts that describe the texture
};

/// How one texture is described.
struct TextureDescription {
    int texture = -1;
    int num_texels = 0;
    std::vector<FeatureScore> features;  ///< all 18, by rank (NaN ones last, in column order)
    std::vector<int> chosen;             ///< indices into `features` of the chosen ones, by rank
    std::string note;                    ///< explanation when the choice is special (one texel:
                                         ///< every defined S is 0, ties broken by column order)
};

/// Describes every texture. `features` is #texels by 18 (FeatureTable::values),
/// `texel_texture` #texels with ids in [0, num_textures). Ties of S are broken by feature
/// column order. Deterministic. Throws InvalidInput on mismatched sizes or labels.
std::vector<TextureDescription> describe_textures(const Eigen::MatrixXd& features,
                                                  const std::vector<int>& texel_texture, int num_textures,
                                                  const Dictionary& dictionary,
                                                  const DescriptionParams& params = {});

}  // namespace geotex
