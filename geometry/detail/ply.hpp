#pragma once
/// Hand-written PLY reader (ASCII, binary little and big endian) behind read_mesh_memory.

#include <string>
#include <string_view>

#include "geometry/mesh_io.hpp"

namespace geotex::detail {

/// Parses a whole PLY file held in memory. `name` goes into the errors. Returns the vertex
/// positions and the polygons of the `face` element (its `vertex_indices` or `vertex_index`
/// list), both given to `sink` instead when it is set, and, without a sink, the scalar face
/// properties converted to double; every other element and property is skipped. Throws
/// ParseError with the place of the first problem (header and ASCII body: line and column;
/// binary body: element, index and byte offset in the message).
MeshFile read_ply(std::string_view data, const std::string& name, const PolygonSink& sink);

}  // namespace geotex::detail
