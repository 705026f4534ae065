#pragma once
// The options of the choice of concepts (docs/words.md), shared by `annotate` and `batch`.

#include <string>

#include "annotation/significance.hpp"
#include "ontology/rdf_writer.hpp"

// CLI11 declared only: it is header-only, and every source that includes it pays seconds of
// compile time (15 s under the sanitizers) even when it uses none of it; the sources that
// register options include <CLI/CLI.hpp> themselves.
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace geotex::cli {

/// Adds --concepts, --max-significance, --min-agreement, --min-stability and --resamples.
void add_description_options(CLI::App& sub, DescriptionParams& p);

/// The options as one line of text (for digests and stamps): every field, fixed format.
std::string description_params_text(const DescriptionParams& p);

/// The value of --mesh-unit ("" = not said); throws CliError (usage) naming the option and
/// the units it takes.
MeshUnit checked_mesh_unit(const std::string& text);

}  // namespace geotex::cli
