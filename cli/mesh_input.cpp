#include "cli/mesh_input.hpp"

#include <algorithm>

#include "geometry/unit_frame.hpp"

namespace geotex::cli {

namespace {
char g_current_input[4096];
}  // namespace

void set_current_input(const std::string& path) {
    const std::size_t n = std::min(path.size(), sizeof g_current_input - 1);
    path.copy(g_current_input, n);
    g_current_input[n] = '\0';
}

const char* current_input() { return g_current_input; }

InputMesh load_mesh(const std::string& path, Progress& progress, int repair_tiles) {
    set_current_input(path);
    InputMesh in;
    MeshFile file = timed_stage(progress, "reading", [&] {
        return in_phase(kExitInput, path, [&] { return read_mesh_file(path); });
    });
    in.format = file.format;
    // Before the repair, whose area tests would drop every face of a mesh too small for
    // doubles: a mesh whose size no double holds is refused here, as bad input.
    in_phase(kExitInput, path, [&] { return make_unit_frame(file.soup.positions); });
    in.repaired = timed_stage(progress, "repair", [&] {
        MeshRepairParams params;
        params.tiles = repair_tiles;
        params.keep_sources = false;  // no output reads them
        return in_phase(kExitInput, path,
                        [&] { return repair_soup(std::move(file.soup), params); });
    });
    for (const auto& d : in.repaired.diagnostics) progress.note(path + ": " + d.message);
    return in;
}

}  // namespace geotex::cli
