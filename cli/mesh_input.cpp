#include "cli/mesh_input.hpp"

namespace geotex::cli {

InputMesh load_mesh(const std::string& path, Progress& progress) {
    InputMesh in;
    MeshFile file = timed_stage(progress, "reading", [&] { return in_phase(kExitInput, path, [&] { return read_mesh_file(path); }); });
    in.format = file.format;
    in.repaired = timed_stage(progress, "repair", [&] { return in_phase(kExitInput, path, [&] { return make_mesh(file.soup); }); });
    for (const auto& d : in.repaired.diagnostics) progress.note(path + ": " + d.message);
    return in;
}

}  // namespace geotex::cli
