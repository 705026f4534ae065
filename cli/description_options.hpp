#pragma once
// The options of the choice of concepts (docs/words.md), shared by `annotate` and `batch`.

#include <CLI/CLI.hpp>
#include <string>

#include "annotation/significance.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::cli {

/// Adds --concepts, --max-significance, --min-agreement, --min-stability and --resamples.
void add_description_options(CLI::App& sub, DescriptionParams& p);

/// The options as one line of text (for digests and stamps): every field, fixed format.
std::string description_params_text(const DescriptionParams& p);

/// The value of --mesh-unit ("" = not said); throws CliError (usage) naming the option and
/// the units it takes.
MeshUnit checked_mesh_unit(const std::string& text);

}  // namespace geotex::cli
