#pragma once
// The directory of a tiled run (`--tile-dir DIR`, docs/tiles.md): where each file of the run
// lies, reading those files with errors that name them, refusing a pass whose files are
// missing, the run's key, and the parts joined into a run. Every job of the run and its join
// go through here, so that they agree on the directory's layout.
//
// DIR/mesh.part          the repaired mesh (the mesh pass)
// DIR/mesh.sha256        the mesh file's digest beside its signature
// DIR/mesh.extent        the repaired mesh's extent, measured by the mesh pass
// DIR/mesh/tile-K.part   tile K's mesh (the mesh pass)
// DIR/P/tile-K.part      tile K's part of pass P (a kTilePassNames name)
// DIR/P/tile-K.sorted    beside a depth pass's part, its depths sorted
// DIR/P/joined-texels    beside a texel pass's parts, its texels joined once

#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/mesh_input.hpp"
#include "cli/output.hpp"
#include "cli/segment_run.hpp"
#include "geometry/tile_alone.hpp"
#include "geometry/tiled_segmentation.hpp"

namespace geotex::cli {

/// The name of the pass that reads and repairs the mesh once for the others.
inline constexpr const char* kMeshPass = "mesh";

/// DIR/P/tile-K.part: tile `tile`'s (0-based) part of pass `pass`.
std::string part_path(const std::string& dir, TilePass pass, int tile);

/// DIR/P/tile-K.sorted: beside a depth part, its depths sorted (pipeline/sorted_depths.hpp).
std::string sorted_path(const std::string& dir, TilePass pass, int tile);

/// DIR/P/joined-texels: beside texel pass `texel_pass`'s parts, its texels joined once
/// (pipeline/joined_texels.hpp).
std::string joined_texels_path(const std::string& dir, TilePass texel_pass);

/// DIR/mesh.part: the repaired mesh.
std::string mesh_path(const std::string& dir);

/// DIR/mesh.extent: the repaired mesh's extent, which the mesh pass measures for the join
/// (pipeline/prepared_mesh.hpp's write_mesh_extent).
std::string mesh_extent_path(const std::string& dir);

/// DIR/mesh/tile-K.part: tile `tile`'s mesh for the jobs of the passes.
std::string tile_mesh_path(const std::string& dir, int tile);

/// `path` opened for binary reading; IoError when it cannot be.
std::ifstream open_binary_file(const std::string& path);

/// read(in) over the binary file `path` (CliError kExitInput naming the file when it cannot be
/// opened, is of another run, or is damaged).
template <class Read>
auto read_binary_file(const std::string& path, Read&& read) {
    return in_phase(kExitInput, path, [&] {
        std::ifstream in = open_binary_file(path);
        return read(in);
    });
}

/// Tile `tile`'s mesh of the run `key`, read from `path`.
DepthTile read_tile_mesh_file(const std::string& path, const std::string& key, int tile);

/// The run's numbers that the joins of a job need, from the header of tile `tile`'s mesh in
/// DIR alone: a job joins the parts before it reads its tile, so that it does not hold both.
DepthTile read_tile_numbers(const std::string& dir, const std::string& key, int tile);

/// Tile `tile`'s part of pass `pass` of the run `key`, read from `path` (kExitInput naming the
/// file when it is of another run or damaged).
TilePart read_part(const std::string& path, const std::string& key, TilePass pass, int tile);

/// A part source reading DIR's parts of pass `pass`.
TilePartSource parts_of(const std::string& dir, const std::string& key, TilePass pass);

/// Whether DIR holds the part of pass `pass` of each of the `tiles` tiles.
bool all_parts_exist(const std::string& dir, TilePass pass, int tiles);

/// Refuses (kExitInput) a pass with a part missing, naming the tiles and the command that makes
/// them (`mesh` is the mesh file's name, for that command).
void require_parts(const std::string& dir, TilePass pass, int tiles, const std::string& mesh);

/// Refuses (kExitInput) a depth pass whose parts lack their sorted depths (a directory made by
/// a geotex before them), naming the tiles; the pass's job makes them from the parts it finds.
void require_sorted(const std::string& dir, TilePass pass, int tiles, const std::string& mesh);

/// Each orientation's greatest depth of depth pass `pass` over every tile, from the headers of
/// its sorted depths: what picked_depths would otherwise read every part for.
std::vector<double> greatest_depths(const std::string& dir, const std::string& key, TilePass pass,
                                    int tiles);

/// The texels of the texel pass after depth pass `of`, joined once for the jobs after it: read
/// from the pass's joined-texels file when a job has left it (refused, naming it, when it is of
/// another run or damaged), else joined from every tile's part (join_texels, with the run's
/// numbers that `first` carries) and left there for the others. Jobs that start together each
/// join and leave the same file. A pass with a part missing is refused as require_parts
/// refuses it. `stage` names the texels in the progress ("texels").
JoinedTexels texels_joined_once(const std::string& dir, const std::string& key,
                                const DepthTile& first, const SegmentationParams& params,
                                const DepthPassOf& of, const std::string& mesh,
                                const std::string& stage, Progress& progress);

/// What join_parts_until reads of a pass.
enum class JoinFrom {
    Parts,  ///< every tile's part (a run that holds the depth maps merges its own)
    /// For a run kept for its outputs: what the jobs left when it is there, else the parts. Of
    /// a depth pass, the summaries in its sorted depths' headers (add_depth_summary); of a
    /// texel pass, its joined-texels file (finish_texel_pass).
    WhatJobsLeft,
};

/// Joins DIR's parts into `run` until its pass is `until` or later. A pass with a part missing
/// is refused with the parts missing and the command that makes them.
void join_parts_until(TiledSegmentation& run, const std::string& dir, const std::string& key,
                      TilePass until, const std::string& mesh, Progress& progress,
                      JoinFrom from = JoinFrom::Parts);

/// The run's key: the mesh file's digest (from DIR/mesh.sha256 while the file is unchanged,
/// else read and recorded there), the options and the number of tiles.
std::string run_key(const SegmentRunOptions& o);

/// Tells the repair's notes, as the mesh pass gave them, so that every job's log tells them.
void note_repair(const SegmentRunOptions& o, const MeshRepairResult& repaired, Progress& progress);

/// Where outline_tile_mesh puts the positions of mesh.part.
enum class OutlinePositions {
    /// In a scratch file in DIR, read through its mapping: the job does not hold them.
    OnDisk,
    /// OnDisk, or held, with a note, when no file can be made in DIR (a directory the join may
    /// only read).
    OnDiskOrHeld,
    /// OnDisk, and copied again in the order of space with the faces in its places, for the
    /// mesh job's cutting (MeshOutline::placed).
    InSpaceOrder,
};

/// DIR/mesh.part of the run `key` read but for its faces, which stay in the file (refused,
/// naming it, when it is of another run or damaged; a damaged face when it is read).
struct OutlinedTileMesh {
    InputMesh input;            ///< the repaired mesh's report and notes, without its arrays
    std::size_t num_faces = 0;  ///< the faces in the file
    FaceBlockReader faces;      ///< reads them a block at a time; errors name the file
    /// The positions, in a scratch file in DIR (none when OnDiskOrHeld held them in input's
    /// mesh). Shared, so that what reads them can keep the file with it.
    std::shared_ptr<PositionFile> positions;
    /// With OutlinePositions::InSpaceOrder, `positions` copied again in the order of space,
    /// and the faces in its places.
    std::optional<SpaceOrderedPositions> near;
    std::optional<ScratchFile> placed_faces;
};
OutlinedTileMesh outline_tile_mesh(const SegmentRunOptions& o, const std::string& dir,
                                   const std::string& key, Progress& progress,
                                   OutlinePositions where);

/// The mesh of the run `key`: DIR/mesh.part when the mesh pass has made it (refused, naming it,
/// when it is of another run or damaged), else the mesh file read and repaired in o.tiles tiles.
InputMesh load_tile_mesh(const SegmentRunOptions& o, const std::string& dir, const std::string& key,
                         Progress& progress);

}  // namespace geotex::cli
