#pragma once
// Loading a dictionary for a subcommand: a file, or the built-in default.

#include <string>

#include "annotation/dictionary.hpp"

namespace geotex::cli {

/// Reads the whole file as bytes (geotex::read_text_file); CliError kExitInput naming it when
/// it cannot be read.
std::string read_text_file(const std::string& path);

/// SHA-256 of a file read in 1 MiB chunks (a large scan is never held whole); CliError
/// kExitInput naming it when it cannot be read.
std::string sha256_of_file(const std::string& path);

/// The dictionary in `path`, or the built-in default when `path` is empty. Problems are
/// CliErrors with kExitInput, located as file:line:column.
Dictionary load_dictionary(const std::string& path);

}  // namespace geotex::cli
