#pragma once
/// A whole file as one string: the dictionaries, manifests, queries and reports that the
/// command, `geotex batch` and the Python module read.

#include <string>

namespace geotex {

/// The bytes of the file at `path`, unchanged (no newline conversion). Throws IoError naming
/// the file when it is a directory (which would otherwise read as an empty file), cannot be
/// opened (with the system's reason) or a read fails.
std::string read_text_file(const std::string& path);

}  // namespace geotex
