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

/// A dictionary and the text it was parsed from, read once: what a command that edits it
/// (dict fit, the workbench) needs, since an edit rewrites spans of that very text.
struct DictionarySource {
    std::string name;  ///< the file, or kDefaultDictionaryName
    std::string text;
    Dictionary dictionary;
};

/// As load_dictionary, keeping the text.
DictionarySource load_dictionary_source(const std::string& path);

/// The date of a dictionary's new version (stamp_new_version): today in UTC as YYYY-MM-DD, or
/// the day of SOURCE_DATE_EPOCH when set (reproducible builds' convention), so that a test or
/// a script gets the same bytes every day.
std::string version_date();

}  // namespace geotex::cli
