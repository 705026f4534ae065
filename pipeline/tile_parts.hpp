#pragma once
// A tile's part of one pass of a tiled segmentation, on disk (`geotex segment --tiles N
// --tile-dir DIR --pass P`, docs/tiles.md): the jobs of a pass each write the parts of their
// tiles, and the jobs of the next pass, or the merge, read every tile's part of the passes
// before. The file is CBOR (via nlohmann_json) with the arrays as byte strings of little-endian
// numbers, so that a level-11 tile's depths take 8 bytes a value; it carries the run's key,
// and a part of another run is refused rather than mixed in.

#include <iosfwd>
#include <string>

#include "geometry/tiled_segmentation.hpp"

namespace geotex {

/// The key of a tiled run: the geometry cache's key (the geotex version, the mesh file's
/// digest, the parameters) and the number of tiles, so that a part never joins a run of
/// another mesh, other options or another cut.
std::string tile_run_key(const std::string& mesh_sha256, const SegmentationParams& params,
                         int tiles);

/// Writes `part` with the run's key.
void write_tile_part(std::ostream& out, const std::string& key, const TilePart& part);

/// The part held by `bytes` (taken, and freed once parsed), checked to be of the run `key`, of
/// pass `pass` and tile `tile` (0-based). Throws InvalidInput saying what is wrong: not a tile part
/// of this schema, another run's, another pass's or tile's, or damaged. The sizes are checked again
/// when the part joins the run (TiledSegmentation::add).
TilePart read_tile_part(std::string bytes, const std::string& key, TilePass pass, int tile);

}  // namespace geotex
