#include "cli/mesh_input.hpp"

#include <algorithm>

#include "common/errors.hpp"
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

MeshFile read_input(const std::string& path, Progress& progress) {
    set_current_input(path);
    MeshFile file = timed_stage(progress, "reading", [&] {
        return in_phase(kExitInput, path, [&] { return read_mesh_file(path); });
    });
    // Before the repair, whose area tests would drop every face of a mesh too small for
    // doubles: a mesh whose size no double holds is refused here, as bad input.
    in_phase(kExitInput, path, [&] { return make_unit_frame(file.soup.positions); });
    return file;
}

namespace {

MeshRepairParams repair_params(int repair_tiles) {
    MeshRepairParams params;
    params.tiles = repair_tiles;
    params.keep_sources = false;  // no output reads them
    return params;
}

void note_repairs(const std::string& path, const Diagnostics& notes, Progress& progress) {
    for (const auto& d : notes) progress.note(path + ": " + d.message);
}

}  // namespace

InputMesh load_mesh(const std::string& path, Progress& progress, int repair_tiles) {
    MeshFile file = read_input(path, progress);
    InputMesh in;
    in.format = file.format;
    in.repaired = timed_stage(progress, "repair", [&] {
        return in_phase(kExitInput, path, [&] {
            return repair_soup(std::move(file.soup), repair_params(repair_tiles));
        });
    });
    note_repairs(path, in.repaired.diagnostics, progress);
    return in;
}

InputMeshOnDisk repair_on_disk(MeshFile&& file, const std::string& path, Progress& progress,
                               int repair_tiles, const std::string& scratch_dir) {
    const auto repair = [&] {
        try {
            return repair_soup_on_disk(std::move(file.soup), repair_params(repair_tiles),
                                       scratch_dir);
        } catch (const IoError& e) {
            // The scratch directory (a full disk), not the input.
            throw CliError(kExitOutput, e.located());
        }
    };
    InputMeshOnDisk in{
        timed_stage(progress, "repair", [&] { return in_phase(kExitInput, path, repair); }),
        file.format};
    note_repairs(path, in.repaired.diagnostics, progress);
    return in;
}

}  // namespace geotex::cli
