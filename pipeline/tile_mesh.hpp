#pragma once
// A tile's mesh for the jobs of a tiled run's passes, on disk (`geotex segment
// --tiles N --tile-dir DIR --pass mesh` writes DIR/mesh/tile-K.part beside DIR/mesh.part;
// docs/tiles.md): the tile's faces and vertices with a halo of 12r (kTileMeshHaloRadii), their
// ids in the whole mesh, and the whole mesh's choices at them (the fast mode's sampling, the
// connected components). A job of a pass reads its tile's file instead of the whole mesh, so
// that it holds its tile (and, for the texels, every vertex's depth), not the whole mesh.
//
// The file is laid out as DIR/mesh.part (pipeline/detail/framed_file.hpp): a line "geotex tile
// mesh", a CBOR header (the run's key, the tile, the boxes, the counts, the radius, the
// sampling grid),
// then little-endian arrays: positions (#V_tile by 3 doubles), the vertices' ids in the whole
// mesh (#V_tile 32-bit), a byte of flags a vertex (owned, complete, sampled), the components
// (#V_tile 32-bit), faces (#F_tile by 3 32-bit), the faces' ids (#F_tile 32-bit) and a byte a
// face (owned): 33 bytes a vertex and 17 a face.

#include <iosfwd>
#include <string>

#include "geometry/tiled_segmentation.hpp"

namespace geotex {

/// Writes `tile` with the run's key.
void write_tile_mesh(std::ostream& out, const std::string& key, const DepthTile& tile);
/// The same for a tile given by its numbers (a DepthTile whose arrays are not read) and its
/// rows, for one that is not held (TiledSegmentation::spool_depth_tile): the same bytes.
void write_tile_mesh(std::ostream& out, const std::string& key, const DepthTile& numbers,
                     const DepthTileRows& rows);

/// The tile held by `in`, checked to be of the run `key` and tile `tile` (0-based). Throws
/// InvalidInput saying what is wrong: not a tile mesh of this schema, another run's or
/// another tile's, or damaged (truncated, bytes past the end, a coordinate that is not finite,
/// an index out of range, ids that do not ascend).
DepthTile read_tile_mesh(std::istream& in, const std::string& key, int tile);

/// The tile held by `in` without its mesh: the run's numbers (the boxes, the whole mesh's
/// vertex count, r, the halo, the sampling grid) that the joins of a job need, read from the
/// header alone and checked as read_tile_mesh checks them, the arrays' length included.
DepthTile read_tile_mesh_numbers(std::istream& in, const std::string& key, int tile);

}  // namespace geotex
