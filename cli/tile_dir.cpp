#include "cli/tile_dir.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>
#include <utility>

#include "pipeline/file_digest.hpp"
#include "pipeline/joined_texels.hpp"
#include "pipeline/prepared_mesh.hpp"
#include "pipeline/read_text_file.hpp"
#include "pipeline/sorted_depths.hpp"
#include "pipeline/tile_mesh.hpp"
#include "pipeline/tile_parts.hpp"

namespace geotex::cli {

namespace {

namespace fs = std::filesystem;

// DIR/SUB/tile-K.EXT: tile `tile`'s file of a pass (SUB the pass's name) or of the mesh pass.
std::string tile_file(const std::string& dir, const std::string& sub, int tile,
                      const char* extension) {
    return (fs::path(dir) / sub / ("tile-" + std::to_string(tile + 1) + extension)).string();
}

bool before(TilePass a, TilePass b) { return static_cast<int>(a) < static_cast<int>(b); }

// The tiles (0-based) whose file path_of(dir, pass, tile) DIR lacks.
std::vector<int> absent_files(const std::string& dir, TilePass pass, int tiles,
                              std::string (*path_of)(const std::string&, TilePass, int)) {
    std::vector<int> absent;
    for (int b = 0; b < tiles; ++b)
        if (!fs::exists(path_of(dir, pass, b))) absent.push_back(b);
    return absent;
}

// Refuses a pass with tiles `absent` lacking `what`, naming them and the command to run.
void refuse_absent(const std::string& dir, TilePass pass, int tiles, const std::vector<int>& absent,
                   const std::string& what, const std::string& mesh, const std::string& then) {
    if (absent.empty()) return;
    throw CliError(kExitInput, (fs::path(dir) / name_of(pass)).string() + ": " +
                                   (absent.size() == 1 ? "tile " : "tiles ") +
                                   tile_numbers(absent) + " of " + std::to_string(tiles) +
                                   (absent.size() == 1 ? " has" : " have") + " no " + what +
                                   "; run `geotex segment " + mesh + " ... --tile-dir " + dir +
                                   " --pass " + name_of(pass) + "` with the same options " + then);
}

// DIR/mesh.sha256: the mesh file's digest beside its signature (file_signature) when it was
// read. Every job of a run needs the digest for the run's key, and reading a level-11 sphere's
// 2.1 GB for it took each job 1-4 s; a job finding the record with the file's signature
// unchanged takes the digest from it.
constexpr const char* kDigestRecord = "mesh.sha256";
constexpr std::string_view kDigestRecordHeader = "geotex mesh digest 1";

bool is_sha256_hex(const std::string& s) {
    return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

// The mesh file's digest, from DIR's record while the file is unchanged, else read (and then
// recorded, when DIR exists and the file did not change while it was read).
std::string mesh_digest(const SegmentRunOptions& o) {
    const std::string record = (fs::path(o.tile_dir) / kDigestRecord).string();
    const std::optional<std::string> signature = file_signature(o.mesh);
    if (signature) {
        std::ifstream in(record, std::ios::binary);
        std::string header, recorded, digest;
        if (in && std::getline(in, header) && header == kDigestRecordHeader &&
            std::getline(in, recorded) && recorded == *signature && std::getline(in, digest) &&
            is_sha256_hex(digest))
            return digest;
    }
    const std::string digest = file_sha256(o.mesh);
    if (signature && file_signature(o.mesh) == signature && fs::is_directory(o.tile_dir)) {
        try {
            OutputSet outputs(OutputLinks::Refuse);
            outputs.add(record, [&](std::ostream& out) {
                out << kDigestRecordHeader << '\n' << *signature << '\n' << digest << '\n';
            });
            outputs.commit();
        } catch (const CliError&) {
            // A directory that refuses the record: the digest is right without it.
        }
    }
    return digest;
}

}  // namespace

std::string part_path(const std::string& dir, TilePass pass, int tile) {
    return tile_file(dir, name_of(pass), tile, ".part");
}

std::string sorted_path(const std::string& dir, TilePass pass, int tile) {
    return tile_file(dir, name_of(pass), tile, ".sorted");
}

std::string joined_texels_path(const std::string& dir, TilePass texel_pass) {
    return (fs::path(dir) / name_of(texel_pass) / "joined-texels").string();
}

std::string mesh_path(const std::string& dir) { return (fs::path(dir) / "mesh.part").string(); }

std::string mesh_extent_path(const std::string& dir) {
    return (fs::path(dir) / "mesh.extent").string();
}

std::string tile_mesh_path(const std::string& dir, int tile) {
    return tile_file(dir, kMeshPass, tile, ".part");
}

std::ifstream open_binary_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot open " + path);
    return in;
}

DepthTile read_tile_mesh_file(const std::string& path, const std::string& key, int tile) {
    return read_binary_file(path, [&](std::istream& in) { return read_tile_mesh(in, key, tile); });
}

TilePart read_part(const std::string& path, const std::string& key, TilePass pass, int tile) {
    return in_phase(kExitInput, path,
                    [&] { return read_tile_part(read_text_file(path), key, pass, tile); });
}

bool all_parts_exist(const std::string& dir, TilePass pass, int tiles) {
    return absent_files(dir, pass, tiles, part_path).empty();
}

void require_parts(const std::string& dir, TilePass pass, int tiles, const std::string& mesh) {
    refuse_absent(dir, pass, tiles, absent_files(dir, pass, tiles, part_path), "part", mesh,
                  "first");
}

void require_sorted(const std::string& dir, TilePass pass, int tiles, const std::string& mesh) {
    refuse_absent(dir, pass, tiles, absent_files(dir, pass, tiles, sorted_path),
                  "sorted depths (tile-K.sorted beside tile-K.part)", mesh,
                  "again: it makes them from the parts");
}

std::vector<double> greatest_depths(const std::string& dir, const std::string& key, TilePass pass,
                                    int tiles) {
    std::vector<double> greatest;
    for (int b = 0; b < tiles; ++b) {
        const std::string path = sorted_path(dir, pass, b);
        const SortedDepthsFile file =
            in_phase(kExitInput, path, [&] { return SortedDepthsFile(path, key, pass, b); });
        if (b == 0) greatest.assign(file.orientations(), 0.0);
        if (file.orientations() != greatest.size())
            throw CliError(kExitInput, path + ": the depths of " +
                                           std::to_string(file.orientations()) +
                                           " orientations, not " + std::to_string(greatest.size()));
        for (std::size_t i = 0; i < greatest.size(); ++i)
            greatest[i] = std::max(greatest[i], file.greatest()[i]);
    }
    return greatest;
}

namespace {

// Texel pass `pass`'s joined texels of the run `key`, read from `path` (kExitInput naming it
// when it is of another run or damaged).
JoinedTexels read_joined_texels_file(const std::string& path, const std::string& key,
                                     TilePass pass) {
    return read_binary_file(path,
                            [&](std::istream& in) { return read_joined_texels(in, key, pass); });
}

}  // namespace

JoinedTexels texels_joined_once(const std::string& dir, const std::string& key,
                                const DepthTile& first, const SegmentationParams& params,
                                const DepthPassOf& of, const std::string& mesh,
                                const std::string& stage, Progress& progress) {
    const TilePass pass = texel_pass_after(of.pass);
    require_parts(dir, pass, first.boxes.size(), mesh);
    const std::string path = joined_texels_path(dir, pass);
    if (fs::exists(path))
        return timed_stage(progress, "reading the joined " + stage,
                           [&] { return read_joined_texels_file(path, key, pass); });
    JoinedTexels joined = timed_stage(progress, "joining the " + stage, [&] {
        return in_phase(kExitInput, (fs::path(dir) / name_of(pass)).string(),
                        [&] { return join_texels(first, params, of, parts_of(dir, key, pass)); });
    });
    OutputSet outputs(OutputLinks::Refuse);
    outputs.add(path, [&](std::ostream& out) { write_joined_texels(out, key, pass, joined); });
    outputs.commit();
    return joined;
}

namespace {

// The summaries of depth pass `pass` in its sorted depths' headers, one a tile; none when a
// tile's file is missing or was made before it kept them.
std::optional<std::vector<DepthPartSummary>> depth_summaries(const std::string& dir,
                                                             const std::string& key, TilePass pass,
                                                             int tiles) {
    if (!absent_files(dir, pass, tiles, sorted_path).empty()) return std::nullopt;
    std::vector<DepthPartSummary> out;
    for (int b = 0; b < tiles; ++b) {
        const std::string path = sorted_path(dir, pass, b);
        const std::optional<DepthPartSummary> summary = in_phase(
            kExitInput, path, [&] { return SortedDepthsFile(path, key, pass, b).summary(); });
        if (!summary) return std::nullopt;
        out.push_back(*summary);
    }
    return out;
}

}  // namespace

void join_parts_until(TiledSegmentation& run, const std::string& dir, const std::string& key,
                      TilePass until, const std::string& mesh, Progress& progress, JoinFrom from) {
    while (before(run.pass(), until)) {
        const TilePass pass = run.pass();
        require_parts(dir, pass, run.num_tiles(), mesh);
        const std::string joined = joined_texels_path(dir, pass);
        const bool summaries = from == JoinFrom::WhatJobsLeft;
        if (summaries && is_texel_pass(pass) && fs::exists(joined)) {
            timed_stage(progress, std::string("reading the joined texels of pass ") + name_of(pass),
                        [&] {
                            JoinedTexels read = read_joined_texels_file(joined, key, pass);
                            in_phase(kExitInput, joined,
                                     [&] { run.finish_texel_pass(std::move(read.texels)); });
                        });
            continue;
        }
        if (summaries && is_depth_pass(pass)) {
            // The greatest depths and counts are all the outputs take of a depth part. Their
            // headers are read before the stage is named, so that a join that falls back to the
            // parts says only that.
            const auto all = depth_summaries(dir, key, pass, run.num_tiles());
            if (all) {
                timed_stage(progress, std::string("reading the summaries of pass ") + name_of(pass),
                            [&] {
                                for (const DepthPartSummary& s : *all)
                                    in_phase(kExitInput, sorted_path(dir, pass, s.tile),
                                             [&] { run.add_depth_summary(s); });
                                in_phase(kExitProcessing, mesh, [&] { run.finish_pass(); });
                            });
                continue;
            }
        }
        timed_stage(progress, std::string("joining pass ") + name_of(pass), [&] {
            for (int b = 0; b < run.num_tiles(); ++b) {
                const std::string path = part_path(dir, pass, b);
                TilePart part = read_part(path, key, pass, b);
                in_phase(kExitInput, path, [&] { run.add(std::move(part)); });
            }
            in_phase(kExitProcessing, mesh, [&] { run.finish_pass(); });
        });
    }
}

std::string run_key(const SegmentRunOptions& o) {
    return in_phase(kExitInput, o.mesh,
                    [&] { return tile_run_key(mesh_digest(o), o.params, o.tiles); });
}

void note_repair(const SegmentRunOptions& o, const MeshRepairResult& repaired, Progress& progress) {
    for (const auto& d : repaired.diagnostics) progress.note(o.mesh + ": " + d.message);
}

InputMesh load_tile_mesh(const SegmentRunOptions& o, const std::string& dir, const std::string& key,
                         Progress& progress) {
    const std::string path = mesh_path(dir);
    if (!fs::exists(path)) return load_mesh(o.mesh, progress, o.tiles);
    set_current_input(o.mesh);
    PreparedMesh prepared = timed_stage(progress, "reading the repaired mesh", [&] {
        return read_binary_file(path,
                                [&](std::istream& in) { return read_prepared_mesh(in, key); });
    });
    note_repair(o, prepared.repaired, progress);
    return {std::move(prepared.repaired), std::move(prepared.format)};
}

OutlinedTileMesh outline_tile_mesh(const SegmentRunOptions& o, const std::string& dir,
                                   const std::string& key, Progress& progress,
                                   OutlinePositions where) {
    const std::string path = mesh_path(dir);
    set_current_input(o.mesh);
    OutlinedTileMesh out;
    auto file = std::make_shared<std::ifstream>();
    PreparedOutline outline = timed_stage(progress, "reading the repaired mesh's vertices", [&] {
        if (where != OutlinePositions::OnDiskOrHeld) {
            on_scratch([&] { out.positions = std::make_shared<PositionFile>(dir); });
        } else {
            try {
                out.positions = std::make_shared<PositionFile>(dir);
            } catch (const IoError& e) {
                progress.note(e.located() + "; the vertices are held in memory");
            }
        }
        return in_phase(kExitInput, path, [&] {
            *file = open_binary_file(path);
            return on_scratch(
                [&] { return read_prepared_outline(*file, key, out.positions.get()); });
        });
    });
    out.input = {std::move(outline.mesh.repaired), std::move(outline.mesh.format)};
    out.num_faces = outline.num_faces;
    // The outline is copied without its arrays, moved out above.
    out.faces = [file, outline, path](std::size_t first, std::size_t count,
                                      std::vector<std::array<int, 3>>& faces) {
        in_phase(kExitInput, path,
                 [&] { read_prepared_faces(*file, outline, first, count, faces); });
    };
    if (where == OutlinePositions::InSpaceOrder)
        timed_stage(progress, "copying the mesh in the order of space", [&] {
            on_scratch([&] {
                out.near.emplace(out.positions->positions(), dir);
                out.placed_faces.emplace(
                    faces_in_places(out.faces, out.num_faces, out.near->places(), dir));
            });
        });
    return out;
}

DepthTile read_tile_numbers(const std::string& dir, const std::string& key, int tile) {
    return read_binary_file(tile_mesh_path(dir, tile), [&](std::istream& in) {
        return read_tile_mesh_numbers(in, key, tile);
    });
}

TilePartSource parts_of(const std::string& dir, const std::string& key, TilePass pass) {
    return [dir, key, pass](int k) { return read_part(part_path(dir, pass, k), key, pass, k); };
}

}  // namespace geotex::cli
