#pragma once
/// Reading the name tables of the pipeline's enumerations. Each table sits beside its enum's
/// declaration (kOrientationModeNames in segmentation.hpp, ...) and is the one spelling of
/// those names for the options, the reports and the RDF literals; its first entry is the
/// one the command line lists first.

#include <array>
#include <optional>
#include <string_view>
#include <utility>

namespace geotex {

/// The name of `value` in `table`; nullptr if the table lacks it (a table covers its enum).
template <class Enum, std::size_t N>
constexpr const char* name_in(const std::array<std::pair<const char*, Enum>, N>& table,
                              Enum value) {
    for (const auto& entry : table)
        if (entry.second == value) return entry.first;
    return nullptr;
}

/// The value named `name` in `table` (exact spelling); nullopt for any other name.
template <class Enum, std::size_t N>
constexpr std::optional<Enum> value_in(const std::array<std::pair<const char*, Enum>, N>& table,
                                       std::string_view name) {
    for (const auto& entry : table)
        if (name == entry.first) return entry.second;
    return std::nullopt;
}

}  // namespace geotex
