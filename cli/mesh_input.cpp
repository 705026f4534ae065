#include "cli/mesh_input.hpp"

#include "geometry/unit_frame.hpp"

namespace geotex::cli {

InputMesh load_mesh(const std::string& path, Progress& progress) {
    InputMesh in;
    MeshFile file = timed_stage(progress, "reading", [&] { return in_phase(kExitInput, path, [&] { return read_mesh_file(path); }); });
    in.format = file.format;
    // Before the repair, whose area tests would drop every face of a mesh too small for
    // doubles: a mesh whose size no double holds is refused here, as bad input.
    in_phase(kExitInput, path, [&] { return make_unit_frame(file.soup.positions); });
    in.repaired = timed_stage(progress, "repair", [&] { return in_phase(kExitInput, path, [&] { return make_mesh(file.soup); }); });
    for (const auto& d : in.repaired.diagnostics) progress.note(path + ": " + d.message);
    return in;
}

}  // namespace geotex::cli
