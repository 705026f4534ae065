#pragma once
// `geotex segment --tiles N --tile-dir DIR`: the passes of a tiled segmentation run as separate
// jobs (a Slurm array per pass, GNU parallel, or one after another), each job writing its
// tiles' parts of one pass into DIR, and a last run that joins them into the outputs
// (docs/tiles.md). A first job (--pass mesh) reads and repairs the mesh once into
// DIR/mesh.part; every later job reads that, or the mesh file when there is none, and the
// parts of the passes before its own.

#include <string>

#include "cli/output.hpp"
#include "cli/segment_run.hpp"

namespace geotex::cli {

/// What a job of a tiled run does.
struct TileJobOptions {
    std::string dir;         ///< --tile-dir: where the parts are
    std::string pass;        ///< --pass: "mesh", or this pass's parts only (a kTilePassNames name);
                             ///< empty: merge
    int tile = 0;            ///< --tile K: only tile K (1 to N); 0: every tile (or --shard's)
    std::string shard;       ///< --shard i/M: the tiles K with (K - 1) mod M = i - 1
    bool dir_given = false;  ///< --tile-dir was on the command line (perhaps empty)
    bool pass_given = false;   ///< --pass was on the command line (perhaps empty)
    bool shard_given = false;  ///< --shard was on the command line (perhaps empty)
};

/// Checks the job options against --tiles (CliError kExitUsage).
void check_tile_job_options(const TileJobOptions& job, int tiles);

/// --pass mesh: reads and repairs the mesh and writes it into DIR/mesh.part, unless a mesh of
/// this run is there already. --pass P (a kTilePassNames name): reads the mesh as
/// load_tile_mesh does, rebuilds the run from DIR's parts of the passes before P (refusing
/// missing or mixed parts, kExitInput), then makes P's part of each selected tile that has
/// none and writes it into DIR/P/tile-K.part, all or nothing per part. A pass the run does
/// not need is reported and skipped.
void run_tile_pass(const SegmentRunOptions& o, const TileJobOptions& job, Progress& progress);

/// The mesh and the segmentation joined from DIR's parts of every pass. Throws CliError
/// kExitInput naming the missing parts (and the command that makes them), a part of another
/// run, or a DIR/mesh.part of another run.
SegmentRun merge_tile_parts(const SegmentRunOptions& o, Progress& progress);

}  // namespace geotex::cli
