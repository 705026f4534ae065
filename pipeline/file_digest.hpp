#pragma once
/// SHA-256 of a file, read in chunks (a large scan is never held whole): the mesh digest of
/// the annotation, the dictionary digest and the outputs recorded in batch stamps.

#include <optional>
#include <string>

namespace geotex {

/// Lower-case hexadecimal SHA-256 of the bytes of the file at `path` (64 characters).
/// Throws IoError naming the file when it is a directory, cannot be opened or a read fails.
std::string file_sha256(const std::string& path);

/// What identifies the contents of the file at `path` without reading them, as one line: its
/// size, inode, and modification and change times to the nanosecond ("size 524288318 inode
/// 1234 mtime 1764870000.123456789 ctime ..."). Any write to the file, a `touch` or another
/// file under the same name changes it: while it is unchanged, a digest taken earlier still
/// holds, as git trusts its index's stat data. nullopt when `path` is not a regular file.
std::optional<std::string> file_signature(const std::string& path);

}  // namespace geotex
