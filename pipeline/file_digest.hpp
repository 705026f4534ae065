#pragma once
/// SHA-256 of a file, read in chunks (a large scan is never held whole): the mesh digest of
/// the annotation, the dictionary digest and the outputs recorded in batch stamps.

#include <string>

namespace geotex {

/// Lower-case hexadecimal SHA-256 of the bytes of the file at `path` (64 characters).
/// Throws IoError naming the file when it is a directory, cannot be opened or a read fails.
std::string file_sha256(const std::string& path);

}  // namespace geotex
