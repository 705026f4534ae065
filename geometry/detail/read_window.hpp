#pragma once
// The pages of a mesh file behind its reader, given back as the reader goes (read_mesh_file
// maps the file; these live beside the mapping, in mapped_file.cpp): reading a large scan then
// holds a window of the file's bytes, not every page of it that the reader has passed
// (sphere-1 level 11: a 2.0 GB PLY).

#include <cstddef>

namespace geotex::detail {

/// The reader of the file that read_mesh_file holds on this thread will not look before `p`
/// again: the file's bytes before it may leave memory, in steps of kReleaseStep. Nothing when
/// `p` is not in such a file (read_mesh_memory's bytes are the caller's). Cheap between steps:
/// call it every few thousand records or lines, with the start of the current one.
void release_read(const void* p);

/// A reader that scans the file before it parses it (the OBJ reader counts its lines to
/// reserve) has scanned it up to `p`: the pages before it may leave memory, in steps of
/// kReleaseStep, and are read from the file again when the parse comes to them. Nothing when
/// `p` is not in a file that read_mesh_file holds.
void release_scanned(const void* p);

/// The bytes a step gives back (whole pages).
constexpr std::size_t kReleaseStep = std::size_t{16} << 20;

/// The bytes given back on this thread so far, for the tests.
std::size_t released_read_bytes();

}  // namespace geotex::detail
