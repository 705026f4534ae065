#pragma once
// Reading and repairing an input mesh for a subcommand, with its errors located in the file.

#include <string>

#include "cli/output.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"

namespace geotex::cli {

struct InputMesh {
    MeshRepairResult repaired;
    std::string format;
};

/// Records `path` as the file the command works on: errors that arise far from any file
/// (out of memory) name it. Kept in fixed storage, so that reading it needs no allocation.
void set_current_input(const std::string& path);

/// The file last recorded by set_current_input ("" before any).
const char* current_input();

/// Reads `path` (recorded as the current input) and repairs it; problems are CliErrors with
/// kExitInput naming the file. Repairs are reported on stderr through `progress`.
/// `repair_tiles` above 1 repairs it in that many tiles (MeshRepairParams::tiles), for a
/// lower peak; the same mesh.
InputMesh load_mesh(const std::string& path, Progress& progress, int repair_tiles = 1);

struct InputMeshOnDisk {
    RepairedOnDisk repaired;
    std::string format;
};

/// load_mesh with the faces on disk, in scratch files in the directory `scratch_dir`: the
/// polygons go there as they are read (a PolygonSink), and the repair reads them from there
/// (repair_soup_on_disk). For the mesh job of a tiled run, which then holds a scan's positions,
/// not its faces. A scratch file that cannot be written is a CliError with kExitOutput naming
/// the directory.
InputMeshOnDisk load_mesh_on_disk(const std::string& path, Progress& progress, int repair_tiles,
                                  const std::string& scratch_dir);

}  // namespace geotex::cli
