#include "cli/mesh_input.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "common/release.hpp"
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

namespace {

// Reads `path` (recorded as the current input), its polygons and positions to `sink` when it
// is set.
MeshFile read_input(const std::string& path, Progress& progress, const PolygonSink& sink = {}) {
    set_current_input(path);
    return timed_stage(progress, "reading", [&] {
        return in_phase(kExitInput, path, [&] { return read_mesh_file(path, sink); });
    });
}

// Refuses, as bad input, a mesh of `path` whose size no double holds: before the repair, whose
// area tests would drop every face of a mesh too small for doubles.
void check_unit_frame(const std::string& path, PositionSpan positions) {
    in_phase(kExitInput, path, [&] { return make_unit_frame(positions); });
}

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
    check_unit_frame(path, file.soup.positions);
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

InputMeshOnDisk load_mesh_on_disk(const std::string& path, Progress& progress, int repair_tiles,
                                  const std::string& scratch_dir) {
    SoupOnDisk soup = on_scratch([&] { return SoupOnDisk(scratch_dir); });
    MeshFile file = read_input(
        path, progress, [&](const PolygonSoup& block) { on_scratch([&] { soup.append(block); }); });
    // An STL file's positions, which its reader holds (the others' went to the sink): the
    // repair reads them from disk, so they are not held beside its steps.
    on_scratch([&] { soup.positions.append(file.soup.positions); });
    release(file.soup.positions);
    check_unit_frame(path, on_scratch([&] { return soup.positions.positions(); }));
    const auto repair = [&] {
        return on_scratch([&] {
            return repair_soup_on_disk(std::move(soup), repair_params(repair_tiles), scratch_dir);
        });
    };
    InputMeshOnDisk in{
        timed_stage(progress, "repair", [&] { return in_phase(kExitInput, path, repair); }),
        file.format};
    note_repairs(path, in.repaired.diagnostics, progress);
    return in;
}

}  // namespace geotex::cli
