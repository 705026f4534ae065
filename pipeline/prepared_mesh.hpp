#pragma once
// The repaired mesh of a tiled run, on disk (`geotex segment --tiles N --tile-dir DIR --pass
// mesh`, docs/tiles.md): one job reads and repairs the mesh once, and the jobs of the passes
// and the merge read the mesh from DIR/mesh.part instead of reading and repairing it again.
// Repair (orientation above all) is a whole-mesh step whose scratch memory is about twice the
// mesh's, so a job that skips it needs only the mesh itself: at sphere-1 level 9 the floor
// of a job falls by about three fifths (bench/RESULTS.md).
//
// The file: a line "geotex prepared mesh", the length of a CBOR header as 8 little-endian
// bytes, the header (the run's key, the counts, the mesh's format, the repair's report and
// notes), then the positions as little-endian doubles (#V by 3) and the faces as
// little-endian 32-bit indices (#F by 3). The arrays are raw, not in the CBOR, so that they
// are read straight into the mesh: a CBOR byte string would be held twice while read.

#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "geometry/face_blocks.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/topology.hpp"

namespace geotex {

/// A mesh as the jobs of a tiled run read it: the repair's result (without source_polygon,
/// which the segmentation does not read) and the format of the file it came from.
struct PreparedMesh {
    MeshRepairResult repaired;
    std::string format;  ///< "PLY", "OBJ", ... as read_mesh_file named it
};

/// Writes `mesh` with the run's key.
void write_prepared_mesh(std::ostream& out, const std::string& key, const PreparedMesh& mesh);

/// The same for a mesh that is not held (mesh.repaired.mesh is not read): its `positions`,
/// perhaps mapped from a file, and its `num_faces` faces from `faces` a block at a time (the
/// mesh job's repair on disk).
void write_prepared_mesh(std::ostream& out, const std::string& key, const PreparedMesh& mesh,
                         PositionSpan positions, const FaceBlockReader& faces,
                         std::size_t num_faces);

/// The mesh held by `in`, checked to be of the run `key`. Throws InvalidInput saying what is
/// wrong: not a prepared mesh of this schema, another run's, or damaged (truncated, bytes past
/// the end, an index out of range, a coordinate that is not finite).
PreparedMesh read_prepared_mesh(std::istream& in, const std::string& key);

/// A prepared mesh read but for its faces, which stay in the file (read_prepared_faces): the
/// join of a tiled run holds 24 bytes a vertex, not 24 more a face with the faces and their
/// labels.
struct PreparedOutline {
    PreparedMesh mesh;             ///< repaired.mesh.faces empty
    std::size_t num_vertices = 0;  ///< #V in the file, also once the positions are moved out
    std::size_t num_faces = 0;     ///< #F in the file
    std::uint64_t faces_at = 0;    ///< the offset of the faces in the file
};

/// The header and positions of the prepared mesh in `in` (checked as read_prepared_mesh checks
/// them, and the file's length against its counts); its faces are not read. With `positions`,
/// the positions go there instead of into mesh.repaired.mesh (the mesh job of a tiled run,
/// which does not hold them), with PositionFile's errors besides.
PreparedOutline read_prepared_outline(std::istream& in, const std::string& key,
                                      PositionFile* positions = nullptr);

/// Faces [first, first + count) of the prepared mesh in `in` outlined by `outline`, into `out`.
/// Throws InvalidInput when the range is past the last face, the file ends inside it or a
/// face names a vertex past the last.
void read_prepared_faces(std::istream& in, const PreparedOutline& outline, std::size_t first,
                         std::size_t count, std::vector<std::array<int, 3>>& out);

/// Beside DIR/mesh.part, its extent (DIR/mesh.extent): what make_mesh_extent measures (the
/// bounding box, the largest side, the mean edge length, the counts), which the mesh job
/// measures once and the join of the outputs reads instead of measuring again. The measure
/// reads the positions in the order of the faces, which wants most of them in the page cache
/// (1 GB at sphere-1 level 11). A framed header alone, with the run's key; the numbers as
/// their bits, so that they read back exactly. The arrays of `extent` are not written.
void write_mesh_extent(std::ostream& out, const std::string& key, const MeshMetrics& extent);

/// The extent in `in`, checked to be the run `key`'s. Throws InvalidInput saying what is wrong:
/// not a mesh extent of this schema, another run's, or damaged (a number that is not finite, a
/// negative count, bytes past its end).
MeshMetrics read_mesh_extent(std::istream& in, const std::string& key);

}  // namespace geotex
