#pragma once
/// Reading polygon meshes from PLY (ASCII and binary), OFF, OBJ and STL, and writing PLY.
/// Readers validate what they read (index range, finite coordinates, declared counts against
/// the file size, and for PLY and OFF no data beyond the declared counts) and throw ParseError
/// with the file and the place of the first problem.

#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/mesh.hpp"

namespace geotex {

/// A scalar per-face property read from a PLY file (e.g. `texel`), converted to double.
struct FaceProperty {
    std::string name;
    std::vector<double> values;  ///< #polygons
};

/// What a mesh file holds.
struct MeshFile {
    PolygonSoup soup;
    std::vector<FaceProperty> face_properties;  ///< PLY scalar face properties, file order
    std::string format;  ///< "ply-ascii", "ply-binary-le", "ply-binary-be", "off", "obj", "stl"
};

/// Reads a mesh file; the format comes from the extension (.ply .off .obj .stl, any case).
/// Throws IoError (cannot open or read), ParseError (malformed content, with the place),
/// InvalidInput (unknown extension).
MeshFile read_mesh_file(const std::string& path);

/// Same, from bytes in memory; `name` is used in error messages and its extension picks
/// the format.
MeshFile read_mesh_memory(std::string_view data, const std::string& name);

/// Type of a per-face scalar written to PLY.
enum class PlyScalarType { Int32, UInt8 };

/// A per-face scalar to write to PLY (values converted to the type).
struct FaceAttribute {
    std::string name;
    PlyScalarType type = PlyScalarType::Int32;
    std::vector<int> values;  ///< #F
};

struct PlyWriteOptions {
    bool binary = true;                 ///< binary little endian, else ASCII
    std::vector<std::string> comments;  ///< header comment lines (no newlines)
};

/// Writes the mesh as PLY with the given face attributes. Vertex coordinates are written
/// as float when every coordinate is exactly representable as float, else as double, so
/// nothing is lost. Throws InvalidInput if an attribute's size is not #F, a UInt8 value is
/// outside 0..255, an attribute name is not a PLY name (printable, no spaces), a face index
/// is out of range or a coordinate is not finite (no PLY reader takes it back); IoError if
/// the stream fails.
void write_ply(std::ostream& out, const Mesh& mesh,
               const std::vector<FaceAttribute>& face_attributes,
               const PlyWriteOptions& options = {});

}  // namespace geotex
