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

#include <iosfwd>
#include <string>

#include "geometry/mesh_repair.hpp"

namespace geotex {

/// A mesh as the jobs of a tiled run read it: the repair's result (without source_polygon,
/// which the segmentation does not read) and the format of the file it came from.
struct PreparedMesh {
    MeshRepairResult repaired;
    std::string format;  ///< "PLY", "OBJ", ... as read_mesh_file named it
};

/// Writes `mesh` with the run's key.
void write_prepared_mesh(std::ostream& out, const std::string& key, const PreparedMesh& mesh);

/// The mesh held by `in`, checked to be of the run `key`. Throws InvalidInput saying what is
/// wrong: not a prepared mesh of this schema, another run's, or damaged (truncated, bytes past
/// the end, an index out of range, a coordinate that is not finite).
PreparedMesh read_prepared_mesh(std::istream& in, const std::string& key);

}  // namespace geotex
