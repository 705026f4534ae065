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

/// Reads `path` and repairs it; problems are CliErrors with kExitInput naming the file.
/// Repairs are reported on stderr through `progress`.
InputMesh load_mesh(const std::string& path, Progress& progress);

}  // namespace geotex::cli
