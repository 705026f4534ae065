#pragma once
/// Reading polygon meshes from PLY (ASCII and binary), OFF, OBJ and STL, and writing PLY.
/// Readers validate what they read (index range, finite coordinates, declared counts against
/// the file size, and for PLY and OFF no data beyond the declared counts) and throw ParseError
/// with the file and the place of the first problem.

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <utility>
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
    /// The positions and polygons, but those a PolygonSink took: with one, no polygons, and
    /// no positions but an STL file's
    PolygonSoup soup;
    /// PLY scalar face properties, file order; none when a PolygonSink took the polygons (a
    /// caller that does not hold the faces would not hold 8 bytes a face for each of them)
    std::vector<FaceProperty> face_properties;
    std::string format;  ///< "ply-ascii", "ply-binary-le", "ply-binary-be", "off", "obj", "stl"
};

/// Where a reader puts the polygons and positions it parses when they are not to be held (the
/// mesh job of a tiled run writes them to scratch files, SoupOnDisk): a block at a time, in
/// file order, each the positions and polygons read since the block before (about a million
/// corners or 262,144 positions; the offsets from 0, the indices numbering all the file's
/// positions). The file's soup.face_offsets then stays {0}, and its positions empty, but an
/// STL file's: its reader matches each corner to the positions read before, so it holds them
/// and gives the sink polygons alone. When the reader throws, the sink may have had part of
/// the file; what it throws goes through the reader.
using PolygonSink = std::function<void(const PolygonSoup& block)>;

/// Reads a mesh file; the format comes from the extension (.ply .off .obj .stl, any case).
/// The polygons go to `sink` when it is set, else into the soup. Throws IoError (cannot open
/// or read), ParseError (malformed content, with the place), InvalidInput (unknown extension).
MeshFile read_mesh_file(const std::string& path, const PolygonSink& sink = {});

/// Same, from bytes in memory; `name` is used in error messages and its extension picks
/// the format.
MeshFile read_mesh_memory(std::string_view data, const std::string& name,
                          const PolygonSink& sink = {});

/// Type of a per-face scalar written to PLY.
enum class PlyScalarType { Int32, UInt8 };

/// A per-face scalar to write to PLY (values converted to the type). Its values are its own,
/// or those of an array the caller holds (`shared`), so that the labels of a whole scan are
/// written without a copy of them; either may be mapped through a table, as a texture id is
/// written as one channel of its colour.
struct FaceAttribute {
    FaceAttribute() = default;
    FaceAttribute(std::string name_, PlyScalarType type_, std::vector<int> values_)
        : name(std::move(name_)), type(type_), values(std::move(values_)) {}
    /// Values read from `shared_`, which must outlive write_ply.
    FaceAttribute(std::string name_, PlyScalarType type_, const std::vector<int>* shared_)
        : name(std::move(name_)), type(type_), shared(shared_) {}

    std::string name;
    PlyScalarType type = PlyScalarType::Int32;
    std::vector<int> values;  ///< #F, unless `shared` is given
    /// #F values read instead of `values`. Not owned: it must outlive write_ply.
    const std::vector<int>* shared = nullptr;
    /// When not empty, a face whose value is v is written as table[v - table_first].
    std::vector<int> table;
    int table_first = 0;

    /// The values before the table: `*shared`, or `values`.
    const std::vector<int>& source() const { return shared != nullptr ? *shared : values; }
};

struct PlyWriteOptions {
    bool binary = true;                 ///< binary little endian, else ASCII
    std::vector<std::string> comments;  ///< header comment lines (no newlines)
};

/// Writes the mesh as PLY with the given face attributes. Vertex coordinates are written
/// as float when every coordinate is exactly representable as float, else as double, so
/// nothing is lost. Throws InvalidInput if an attribute's size is not #F, a value is outside
/// its table, a UInt8 value written is outside 0..255, an attribute name is not a PLY name
/// (printable, no spaces), a face index is out of range or a coordinate is not finite (no PLY
/// reader takes it back); IoError if the stream fails.
void write_ply(std::ostream& out, const Mesh& mesh,
               const std::vector<FaceAttribute>& face_attributes,
               const PlyWriteOptions& options = {});

/// Whether every coordinate is exactly a float, so that write_ply writes them as floats.
bool ply_fits_float(PositionSpan positions);

/// write_ply's bytes, a block of vertices or faces at a time, for a mesh whose faces are not
/// held whole (the join of a tiled run reads them from disk). Throws as write_ply, as each
/// block comes (the bytes written by then are not a whole PLY: write into a temporary file),
/// and std::logic_error when the blocks do not add up to the counts of the header.
///
///     PlyWriter ply(out, nv, nf, ply_fits_float(positions), attributes, options);
///     ply.vertices(positions);             // #V in all, in order, one block or more
///     ply.faces(block, block_attributes);  // then #F in all, in order, each attribute #block
///     ply.finish();
class PlyWriter {
  public:
    /// Starts the file with its header: `face_attributes` give the properties' names and
    /// types (not their values); every block's attributes must have the same, in that order.
    PlyWriter(std::ostream& out, std::size_t num_vertices, std::size_t num_faces,
              bool float_coordinates, const std::vector<FaceAttribute>& face_attributes,
              const PlyWriteOptions& options);
    /// The next vertices.
    void vertices(PositionSpan block);
    /// The next faces, after every vertex, with one value a face of each attribute.
    void faces(const std::vector<std::array<int, 3>>& block,
               const std::vector<FaceAttribute>& face_attributes);
    /// Writes what is left, once every vertex and face is in.
    void finish();

  private:
    std::ostream& out_;
    std::size_t num_vertices_, num_faces_;
    bool as_float_, binary_;
    std::vector<PlyScalarType> attribute_types_;
    std::size_t vertices_done_ = 0, faces_done_ = 0;
    std::string buf_;  // the bytes not yet written, about a megabyte at most
};

}  // namespace geotex
