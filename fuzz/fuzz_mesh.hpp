#pragma once
// The body shared by the mesh reader fuzz targets: read, repair, build the topology and the
// metrics, write the repaired mesh as PLY and read it back.

#include <cstddef>
#include <cstdint>

namespace geotex::fuzz {

/// Runs one fuzz input through read_mesh_memory as a file named `name` (its extension picks
/// the reader) and through every stage that sees the geometry as read. geotex::Error is an
/// answer; a broken invariant aborts.
int run_mesh_input(const std::uint8_t* data, std::size_t size, const char* name);

}  // namespace geotex::fuzz
