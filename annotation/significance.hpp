#pragma once
/// Significance of the features for each texture and the choice of the concepts that
/// describe it (paper §4.3, with a choice rule that does not flip with the sampling:
/// docs/words.md).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "geometry/depth_map.hpp"

namespace geotex {

/// How concepts are chosen. The paper takes the n = 5 features of lowest S whose mean falls
/// in a labelled interval; when textures are well separated many S are tiny and their order
/// is decided by the sampling. geotex asks, per facet of the dictionary, for the first
/// feature whose concept holds for most of the texture's texels (`min_agreement`), and keeps
/// the concept only when the same choice comes out of most bootstrap resamples of the texels
/// (`min_stability`). S orders the facets for `max_concepts`, and may also be required to be
/// small (`max_significance`): off by default, since it makes a texture's words depend on the
/// other details of its object (docs/words.md).
struct DescriptionParams {
    int max_concepts = 0;         ///< at most this many concepts per texture, the most
                                  ///< significant facets first; 0: one per facet, no cap
    double max_significance = 0;  ///< > 0: a feature whose S is above this does not name
                                  ///< the texture (S = 1: as spread as over all texels);
                                  ///< 0: no such test
    double min_agreement = 0.75;  ///< share of the texture's texels whose own value lies in
                                  ///< the concept's interval (dimensionless, (0, 1])
    double min_stability = 0.9;   ///< share of resamples choosing the same concept for the
                                  ///< facet; below it the concept is withheld, not asserted
    int num_resamples = 200;      ///< bootstrap resamples of the texels of every texture
    std::uint64_t seed = 0x67656f746578ULL;  ///< of the resampling (deterministic)
};

/// One feature of one texture.
struct FeatureScore {
    int feature = -1;         ///< column in kFeatureIds
    double value = 0;         ///< V(i,T): mean of the feature over the texture's texels
    double significance = 0;  ///< S(i,T) = sigma over T / sigma over all texels (population
                              ///< std); NaN when the feature is constant over all texels
    int rank = 0;             ///< 1 = most significant; 0 when S is NaN
    const DictionaryConcept* concept_ptr = nullptr;  ///< interval holding the value, if any
    int facet = -1;         ///< index in Dictionary::facets; -1: the feature has no concept
    double agreement = 0;   ///< share of the texture's texels whose own value lies in
                            ///< concept_ptr's interval (0 without concept)
    double stability = 0;   ///< share of resamples whose choice for this feature's facet is
                            ///< concept_ptr (0 when the rule does not pick this feature)
    bool chosen = false;    ///< asserted: picked by the rule and stable
    bool withheld = false;  ///< picked by the rule on the texture's texels, but less stable
                            ///< than min_stability (or beyond max_concepts): not asserted
};

/// How one texture is described.
struct TextureDescription {
    int texture = -1;
    int num_texels = 0;
    DetailOrientation orientation = DetailOrientation::Positive;  ///< raised or engraved
    std::vector<FeatureScore> features;  ///< all kNumFeatures, by rank (NaN ones last, in
                                         ///< column order)
    std::vector<int> chosen;    ///< indices into `features` of the asserted concepts, by rank;
                                ///< at most one per facet
    std::vector<int> withheld;  ///< indices into `features` of the withheld ones, by rank
    std::string note;           ///< explanation when the choice is special
};

/// Whether a concept of this relief may be said of a detail of this orientation (raised:
/// Positive, engraved: Negative).
bool relief_allows(Relief relief, DetailOrientation orientation);

/// Describes every texture. `features` is #texels by kNumFeatures (FeatureTable::values),
/// `texel_texture` #texels with ids in [0, num_textures), `texture_orientation` #textures
/// (Segmentation::texture_orientation; empty: every texture raised). Deterministic, and the
/// same whatever the order of the texels. Throws InvalidInput on mismatched sizes, labels or
/// parameters out of range.
std::vector<TextureDescription> describe_textures(
    const Eigen::MatrixXd& features, const std::vector<int>& texel_texture, int num_textures,
    const std::vector<DetailOrientation>& texture_orientation, const Dictionary& dictionary,
    const DescriptionParams& params = {});

}  // namespace geotex
