#pragma once
// The options of the choice of concepts (docs/words.md), shared by `annotate` and `batch`.

#include <CLI/CLI.hpp>
#include <string>

#include "annotation/significance.hpp"

namespace geotex::cli {

/// Adds --concepts, --max-significance, --min-agreement, --min-stability and --resamples.
void add_description_options(CLI::App& sub, DescriptionParams& p);

/// The options as one line of text (for digests and stamps): every field, fixed format.
std::string description_params_text(const DescriptionParams& p);

}  // namespace geotex::cli
