#pragma once
// The bytes of a mesh file behind its reader (read_mesh_file), given back as the reader goes:
// reading a large scan then holds its polygons and a window of the file's bytes, not the
// whole file beside them (sphere-1 level 11: a 2.1 GB PLY and 2.3 GB of polygons).

#include <cstddef>

namespace geotex::detail {

/// The reader of the file that read_mesh_file holds on this thread will not look before `p`
/// again: the file's bytes before it may leave memory, in steps of kReleaseStep. Nothing when
/// `p` is not in such a file (read_mesh_memory's bytes are the caller's). Cheap between steps:
/// call it every few thousand records or lines, with the start of the current one.
void release_read(const void* p);

/// The bytes a step gives back (a multiple of the 2 MB pages the file is read into).
constexpr std::size_t kReleaseStep = std::size_t{16} << 20;

/// The bytes given back on this thread so far, for the tests.
std::size_t released_read_bytes();

}  // namespace geotex::detail
