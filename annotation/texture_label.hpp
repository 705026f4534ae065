#pragma once
/// The label of a texture: the one rule of the console summary, the JSON report and the
/// rdfs:label of the RDF, so that the three say the same words in the same language.

#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/significance.hpp"

namespace geotex {

/// A label and its language tag.
struct Label {
    std::string text;      ///< the concepts' labels joined by ", "; empty for no concept
    std::string language;  ///< the tag of every label in `text`; empty when the concepts have
                           ///< no language in common (each then says its own first label)
};

/// The label of a list of concepts, all in one language: `language` when each concept has a
/// label in it, else the first language of dictionary.languages that each has (the first
/// language of the dictionary, for a dictionary that passed parse_dictionary), else the first
/// language of the first concept's labels that each has. Failing all, each concept's first
/// label (its id when it has none), without a language. No concept: an empty label.
/// `concepts` must not hold null pointers.
Label concepts_label(const std::vector<const DictionaryConcept*>& concepts,
                     const Dictionary& dictionary, const std::string& language);

/// concepts_label of the concepts of `texture` at `indices` into texture.features (its
/// `chosen`, for the texture's label, or its `withheld`). Throws InvalidInput when an index
/// is out of range or its feature has no concept.
Label texture_label(const TextureDescription& texture, const std::vector<int>& indices,
                    const Dictionary& dictionary, const std::string& language);

}  // namespace geotex
