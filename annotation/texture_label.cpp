#include "annotation/texture_label.hpp"

#include "common/errors.hpp"

namespace geotex {

Label concepts_label(const std::vector<const DictionaryConcept*>& concepts,
                     const Dictionary& dictionary, const std::string& language) {
    if (concepts.empty()) return {};
    std::vector<std::string> candidates{language};
    candidates.insert(candidates.end(), dictionary.languages.begin(), dictionary.languages.end());
    for (const auto& entry : concepts.front()->labels) candidates.push_back(entry.first);
    for (const std::string& lang : candidates) {
        std::string text;
        bool complete = true;
        for (const DictionaryConcept* c : concepts) {
            const auto it = c->labels.find(lang);
            if (it == c->labels.end()) {
                complete = false;
                break;
            }
            text += (text.empty() ? "" : ", ") + it->second;
        }
        if (complete) return {text, lang};
    }
    std::string text;
    for (const DictionaryConcept* c : concepts)
        text +=
            (text.empty() ? "" : ", ") + (c->labels.empty() ? c->id : c->labels.begin()->second);
    return {text, ""};
}

Label texture_label(const TextureDescription& texture, const std::vector<int>& indices,
                    const Dictionary& dictionary, const std::string& language) {
    std::vector<const DictionaryConcept*> concepts;
    for (int i : indices) {
        if (i < 0 || static_cast<std::size_t>(i) >= texture.features.size() ||
            texture.features[static_cast<std::size_t>(i)].concept_ptr == nullptr)
            throw InvalidInput("texture_label: texture " + std::to_string(texture.texture) +
                               ": feature index " + std::to_string(i) +
                               " is out of range or has no concept");
        concepts.push_back(texture.features[static_cast<std::size_t>(i)].concept_ptr);
    }
    return concepts_label(concepts, dictionary, language);
}

}  // namespace geotex
