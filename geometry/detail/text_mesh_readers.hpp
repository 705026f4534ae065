#pragma once
/// OFF, OBJ and STL readers behind read_mesh_memory: one pass over the bytes that checks and
/// stores at once, with the line and column of the first problem in the ParseError. Numbers
/// are read with std::from_chars (correctly rounded, as istream >> double), so the points are
/// the ones CGAL's stream readers produced before (bench/RESULTS.md: the speeds). Each gives
/// its polygons and positions (STL: its polygons) to `sink` when it is set (mesh_io.hpp), else
/// keeps them in the soup.

#include <string>
#include <string_view>

#include "geometry/mesh_io.hpp"

namespace geotex::detail {

/// OFF (ASCII or OFF BINARY, with optional ST/C/N/4/n prefixes; 4OFF points are divided by
/// their w). Colours, normals and texture coordinates are skipped. Throws ParseError.
MeshFile read_off(std::string_view data, const std::string& name, const PolygonSink& sink);

/// Wavefront OBJ: `v` and `f` statements (with `v/vt/vn` forms and negative relative
/// indices; `v x y z w` and `v x y z r g b` keep x y z); normals, textures, groups and
/// materials are ignored; a backslash at the end of a line continues the statement.
/// Throws ParseError.
MeshFile read_obj(std::string_view data, const std::string& name, const PolygonSink& sink);

/// STL, ASCII or binary; corners with equal coordinates (+0 and -0 equal) become one vertex,
/// numbered in the order of their first appearance. Throws ParseError.
MeshFile read_stl(std::string_view data, const std::string& name, const PolygonSink& sink);

}  // namespace geotex::detail
