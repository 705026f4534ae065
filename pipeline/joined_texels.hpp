#pragma once
// A texel pass's texels joined once, in a file beside its parts (DIR/texels/joined-texels,
// docs/tiles.md): every job after the texel pass used to read every tile's texel part and
// merge the regions again, the 16 jobs of a pass each holding the merge of the whole mesh's
// regions (440 MiB at sphere-1 level 11, 1%). The first job that needs the texels joins them
// and leaves them here; the others, and the join of the outputs, read the texels alone, each
// claimed face once. The layout is the tile meshes' (detail/framed_file.hpp): a CBOR header
// with the run's key, the pass and each orientation's counts and numbers, then the arrays, read
// straight into their vectors.

#include <istream>
#include <ostream>
#include <string>

#include "geometry/tile_alone.hpp"

namespace geotex {

/// Writes texel pass `texel_pass`'s joined texels with the run's key. A set's `face_texel` is
/// not written (a join leaves it empty). Throws InvalidInput when the pass is not a texel pass,
/// or a set's depths are not one a texel.
void write_joined_texels(std::ostream& out, const std::string& key, TilePass texel_pass,
                         const JoinedTexels& joined);

/// The joined texels `in` holds, checked to be the run `key`'s of pass `texel_pass`: what
/// write_joined_texels wrote, bit for bit. Throws InvalidInput saying what is wrong: not such a
/// file, another run's or pass's, of another schema, or damaged (cut short, padded, a texel's
/// faces not ascending, an orientation that is not one).
JoinedTexels read_joined_texels(std::istream& in, const std::string& key, TilePass texel_pass);

}  // namespace geotex
