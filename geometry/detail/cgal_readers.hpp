#pragma once
/// OFF, OBJ and STL readers behind read_mesh_memory: CGAL's stream readers do the parsing,
/// our code checks before (declared sizes, non-finite numbers, with lines) and after (index
/// range, polygon size), because CGAL's readers answer only true or false. CGAL itself is
/// included only by the .cpp, which is slow to compile.

#include <string>
#include <string_view>

#include "geometry/mesh_io.hpp"

namespace geotex::detail {

/// OFF (ASCII or OFF BINARY, with optional ST/C/N prefixes). Throws ParseError.
MeshFile read_off(std::string_view data, const std::string& name);

/// Wavefront OBJ: `v` and `f` statements (with `v/vt/vn` forms and negative relative
/// indices); normals, textures, groups and materials are ignored. Throws ParseError.
MeshFile read_obj(std::string_view data, const std::string& name);

/// STL, ASCII or binary; CGAL merges the bit-identical corners of the triangles. Throws
/// ParseError.
MeshFile read_stl(std::string_view data, const std::string& name);

}  // namespace geotex::detail
