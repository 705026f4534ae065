#include "cli/tile_jobs.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/batch_plan.hpp"
#include "cli/mesh_input.hpp"
#include "cli/tile_dir.hpp"
#include "geometry/tile_alone.hpp"
#include "pipeline/prepared_mesh.hpp"
#include "pipeline/sorted_depths.hpp"
#include "pipeline/tile_mesh.hpp"
#include "pipeline/tile_parts.hpp"

namespace geotex::cli {

namespace {

namespace fs = std::filesystem;

// The pass named `name`; the mesh pass is not one of the segmentation's, and is not asked
// for here.
TilePass pass_named(const std::string& name) {
    const std::optional<TilePass> pass = value_in(kTilePassNames, name);
    if (pass && *pass != TilePass::Done) return *pass;
    std::string names = kMeshPass;
    for (const auto& [n, p] : kTilePassNames)
        if (p != TilePass::Done) names += ", " + std::string(n);
    throw CliError(kExitUsage, "--pass: '" + name + "' is not a pass (" + names + ")");
}

// The extent of the mesh whose positions are `vertices`, measured over the `num_faces` faces of
// `read_faces` a block at a time, which also checks every face of the file `path`.
MeshMetrics measure_extent(PositionSpan vertices, const FaceBlockReader& read_faces,
                           std::size_t num_faces, const std::string& path, Progress& progress) {
    return timed_stage(progress, "measuring the repaired mesh", [&] {
        MeshExtentSum sum(vertices);
        for_each_face_block(read_faces, num_faces,
                            [&](std::size_t, const auto& block) { sum.add(block); });
        return in_phase(kExitInput, path, [&] { return sum.finish(); });
    });
}

// What a run that does not hold the faces of the mesh whose positions are `vertices` takes of
// it: its extent; a look-up of the few faces the join reads; and the blocks, from which the
// mesh job cuts the tiles.
MeshOutline outline_of(PositionSpan vertices, const FaceBlockReader& read_faces,
                       const MeshMetrics& extent) {
    MeshOutline mesh{vertices, extent, {}, read_faces, {}};
    // The faces the join looks up, one a texel, read a short run at a time: ids closer than
    // this share a read, so that no more than the file's faces are read in all.
    mesh.faces = [read_faces](const std::vector<int>& ids) {
        constexpr int kSpan = 4096;
        std::vector<std::array<int, 3>> found, block;
        found.reserve(ids.size());
        for (std::size_t k = 0; k < ids.size();) {
            const int start = ids[k];
            std::size_t end = k + 1;
            while (end < ids.size() && ids[end] - start < kSpan) ++end;
            read_faces(static_cast<std::size_t>(start),
                       static_cast<std::size_t>(ids[end - 1] - start + 1), block);
            for (; k < end; ++k) found.push_back(block[ids[k] - start]);
        }
        return found;
    };
    return mesh;
}

// The mesh read and repaired with its faces in scratch files in DIR, made for them. When it
// fails (a bad mesh), the directories made here (DIR and the parents it lacked) go again,
// deepest first, each only if empty (the scratch files have no name), so that a bad mesh
// leaves nothing behind.
InputMeshOnDisk load_in_new_directory(const SegmentRunOptions& o, const std::string& dir,
                                      Progress& progress) {
    std::vector<fs::path> made;  // deepest first
    std::error_code ec;
    for (fs::path p = fs::absolute(dir, ec); !ec && !p.empty(); p = p.parent_path()) {
        const bool there = fs::exists(p, ec);
        if (ec || there) break;
        made.push_back(p);
        if (p == p.parent_path()) break;
    }
    make_directory(dir);
    try {
        return load_mesh_on_disk(o.mesh, progress, o.tiles, dir);
    } catch (...) {
        for (const fs::path& p : made) fs::remove(p, ec);
        throw;
    }
}

// --pass mesh: the mesh read and repaired into DIR/mesh.part, then cut into tiles
// (DIR/mesh/tile-K.part), so that the jobs of the passes read their tiles instead of the whole
// mesh. The reading and the repair keep the faces in scratch files in DIR, and the
// cutting reads them back from mesh.part a block at a time, for each tile those near it
// (StreamTiler), and writes each tile as its faces are read back from a scratch file: the job
// holds a block of faces and the numbers of one tile's vertices, never the faces or a tile.
void run_mesh_pass(const SegmentRunOptions& o, const std::string& dir, Progress& progress) {
    const std::string key = run_key(o);
    const std::string path = mesh_path(dir);
    const bool made = fs::exists(path);
    if (!made) {
        InputMeshOnDisk input = load_in_new_directory(o, dir, progress);
        RepairedOnDisk& repaired = input.repaired;
        PreparedMesh prepared;
        prepared.repaired.report = repaired.report;
        prepared.repaired.diagnostics = std::move(repaired.diagnostics);
        prepared.format = input.format;
        OutputSet outputs(OutputLinks::Refuse);
        outputs.add(path, [&](std::ostream& out) {
            write_prepared_mesh(out, key, prepared, repaired.positions.positions(),
                                face_reader(repaired.faces), repaired.num_faces);
        });
        outputs.commit();
        std::printf("%s: pass mesh: the repaired mesh written to %s\n", o.mesh.c_str(),
                    path.c_str());
    }
    // A job resubmitted after every tile was cut only checks the files, and needs no copy of
    // the mesh to cut from.
    bool all_cut = made;
    for (int b = 0; all_cut && b < o.tiles; ++b) all_cut = fs::exists(tile_mesh_path(dir, b));
    // Refused when damaged or another run's: the outline checks the header and positions, the
    // measure of the extent every face.
    // The positions are copied to scratch files (in order, and in the order of space, with the
    // faces in their places there for the tiles) and read through their mappings, not held.
    OutlinedTileMesh outlined = outline_tile_mesh(
        o, dir, key, progress, all_cut ? OutlinePositions::OnDisk : OutlinePositions::InSpaceOrder);
    if (made) {
        progress.note(o.mesh + ": pass mesh: made already (" + path + ")");
        note_repair(o, outlined.input.repaired, progress);
    }
    const PositionSpan positions =
        all_cut ? outlined.positions->positions() : outlined.near->positions();
    const MeshMetrics extent =
        measure_extent(positions, outlined.faces, outlined.num_faces, path, progress);
    // Left for the join, which would otherwise measure it again with the positions in the
    // order of the faces (bench/RESULTS.md, "The join takes the extent the mesh job measured").
    const std::string extent_path = mesh_extent_path(dir);
    if (!fs::exists(extent_path)) {
        OutputSet outputs(OutputLinks::Refuse);
        outputs.add(extent_path, [&](std::ostream& out) { write_mesh_extent(out, key, extent); });
        outputs.commit();
    }
    MeshOutline outline = outline_of(positions, outlined.faces, extent);
    if (!all_cut)
        outline.placed = {outlined.near->copy(), face_reader(*outlined.placed_faces),
                          outlined.near->ids()};
    const TiledSegmentation run = in_phase(
        kExitProcessing, o.mesh, [&] { return TiledSegmentation(outline, o.params, o.tiles); });
    make_directory(fs::path(dir) / kMeshPass);
    int cut = 0;
    const std::string stage = "cutting the mesh into tiles";
    timed_stage(progress, stage, [&] {
        const auto start = std::chrono::steady_clock::now();
        for (int b = 0; b < run.num_tiles(); ++b) {
            const std::string tile_path = tile_mesh_path(dir, b);
            if (fs::exists(tile_path)) {  // checked in full, as mesh.part
                read_tile_mesh_file(tile_path, key, b);
                continue;
            }
            // Which tile the stage is at, and the time left at the pace of the tiles cut so
            // far, shown in place on a terminal.
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const std::string left =
                cut > 0 ? ", about " + time_left(seconds, cut, cut + run.num_tiles() - b) + " left"
                        : "";
            progress({stage + ": tile " + std::to_string(b + 1) + "/" +
                          std::to_string(run.num_tiles()) + left,
                      -1.0});
            // The tile goes to its file as its faces are read back from a scratch file in DIR,
            // never held whole (StreamTiler::spool).
            OutputSet outputs(OutputLinks::Refuse);
            in_phase(kExitProcessing, o.mesh, [&] {
                on_scratch([&] {
                    run.spool_depth_tile(b, dir,
                                         [&](const DepthTile& numbers, const DepthTileRows& rows) {
                                             outputs.add(tile_path, [&](std::ostream& out) {
                                                 write_tile_mesh(out, key, numbers, rows);
                                             });
                                         });
                });
            });
            outputs.commit();
            ++cut;
        }
    });
    std::printf("%s: pass mesh: %d tile mesh%s made, %d in all, in %s\n", o.mesh.c_str(), cut,
                cut == 1 ? "" : "es", run.num_tiles(),
                (fs::path(dir) / kMeshPass).string().c_str());
}

// The tiles of a pass the job makes: --tile's, its --shard's, or every tile.
std::vector<int> chosen_tiles(const TileJobOptions& job, int tiles) {
    int shard = 1, shards = 1;
    if (!job.shard.empty()) std::tie(shard, shards) = parse_shard(job.shard);
    std::vector<int> chosen;
    for (int b = 0; b < tiles; ++b)
        if (job.tile != 0 ? b + 1 == job.tile : b % shards == shard - 1) chosen.push_back(b);
    return chosen;
}

// Writes the parts of the chosen tiles of pass `target` that DIR lacks, each made by
// make(tile); a part there already is checked to be of this run and kept.
template <class Make>
void make_parts(const SegmentRunOptions& o, const TileJobOptions& job, const std::string& key,
                TilePass target, const std::vector<int>& chosen, Progress& progress, Make&& make) {
    const fs::path pass_dir = fs::path(job.dir) / job.pass;
    make_directory(pass_dir);
    int made = 0;
    double making = 0;  // seconds spent making the parts made here
    for (std::size_t k = 0; k < chosen.size(); ++k) {
        const int b = chosen[k];
        const std::string path = part_path(job.dir, target, b);
        const std::string which = "tile " + std::to_string(b + 1) + "/" + std::to_string(o.tiles) +
                                  " of pass " + job.pass;
        const std::string sorted = sorted_path(job.dir, target, b);
        const bool with_sorted = is_depth_pass(target);
        if (fs::exists(path)) {
            // Refused when it is of another run: the directory would hold two runs' parts.
            const TilePart part = read_part(path, key, target, b);
            if (with_sorted && !fs::exists(sorted)) {
                // A directory made before the sorted depths: they are made from the part.
                OutputSet outputs(OutputLinks::Refuse);
                outputs.add(sorted,
                            [&](std::ostream& out) { write_sorted_depths(out, key, part); });
                in_phase(kExitProcessing, path, [&] { outputs.commit(); });
                progress.note(o.mesh + ": " + which + ": made already (" + path +
                              "); its sorted depths made from it");
                continue;
            }
            progress.note(o.mesh + ": " + which + ": made already (" + path + ")");
            continue;
        }
        const auto start = std::chrono::steady_clock::now();
        const TilePart part = make(b);
        // The part and its sorted depths are committed together: a job stopped between the
        // two leaves neither.
        OutputSet outputs(OutputLinks::Refuse);
        outputs.add(path, [&](std::ostream& out) { write_tile_part(out, key, part); });
        if (with_sorted)
            outputs.add(sorted, [&](std::ostream& out) { write_sorted_depths(out, key, part); });
        outputs.commit();
        ++made;
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        making += seconds;
        char line[64];
        std::snprintf(line, sizeof line, " (%zu of %zu here): %.1f s", k + 1, chosen.size(),
                      seconds);
        // The tiles after it at the pace of those made so far: a pass of many tiles in one
        // job runs for many minutes.
        const long long after = static_cast<long long>(chosen.size() - k - 1);
        const std::string left = after > 0 ? ", about " + time_left(making, made, made + after) +
                                                 " left for " + std::to_string(after) + " more"
                                           : "";
        progress.note(o.mesh + ": " + which + line + left);
    }
    std::printf("%s: pass %s: %d tile part%s made, %zu chosen, in %s\n", o.mesh.c_str(),
                job.pass.c_str(), made, made == 1 ? "" : "s", chosen.size(),
                pass_dir.string().c_str());
}

// Tile `tile`'s mesh, read from DIR as a stage.
DepthTile read_tile(const std::string& dir, const std::string& key, int tile, Progress& progress) {
    return timed_stage(progress, "reading the mesh of tile " + std::to_string(tile + 1),
                       [&] { return read_tile_mesh_file(tile_mesh_path(dir, tile), key, tile); });
}

// The whole mesh and the run joined up to a pass. The run holds a reference to the mesh, so
// the two stay together, in place.
struct JoinedRun {
    InputMesh input;
    std::optional<TiledSegmentation> run;
};

// The whole mesh (mesh.part, or read and repaired) with every part of the passes before
// `target` joined.
std::unique_ptr<JoinedRun> join_passes(const SegmentRunOptions& o, const std::string& dir,
                                       const std::string& key, TilePass target,
                                       Progress& progress) {
    auto joined = std::make_unique<JoinedRun>();
    joined->input = load_tile_mesh(o, dir, key, progress);
    joined->run.emplace(in_phase(kExitProcessing, o.mesh, [&] {
        return TiledSegmentation(joined->input.repaired.mesh, o.params, o.tiles);
    }));
    join_parts_until(*joined->run, dir, key, target, o.mesh, progress);
    return joined;
}

// Tile parts made from the whole mesh, for the tiles whose texels outgrow them: the mesh is
// read, and the parts of the passes before joined, once for the job.
class WholeMeshFallback {
  public:
    // Tile `tile`'s part of pass `target`, saying why the whole mesh is read.
    TilePart part(const SegmentRunOptions& o, const std::string& dir, const std::string& key,
                  TilePass target, int tile, const std::string& why, Progress& progress) {
        progress.note(o.mesh + ": tile " + std::to_string(tile + 1) + ": " + why +
                      "; the whole mesh is read for it");
        if (!whole_) whole_ = join_passes(o, dir, key, target, progress);
        return in_phase(kExitProcessing, o.mesh, [&] { return whole_->run->run_tile(tile); });
    }

  private:
    std::unique_ptr<JoinedRun> whole_;
};

// The parts of the texel pass after depth pass `of` from the tile meshes: the seeds'
// thresholds merged from every tile's sorted depths (a block of each held, not the whole
// mesh's depths) by the pass's first job, which leaves them for the others; each tile's depths
// picked from the parts around it; and the regions grown in the tile. A tile whose regions grow
// past its halo is made from the whole mesh, read for it once.
void make_texel_parts(const SegmentRunOptions& o, const TileJobOptions& job, const std::string& key,
                      const std::vector<int>& chosen, const DepthPassOf& of, Progress& progress) {
    require_parts(job.dir, of.pass, o.tiles, o.mesh);
    require_sorted(job.dir, of.pass, o.tiles, o.mesh);
    const TilePartSource part_of = parts_of(job.dir, key, of.pass);
    const SortedDepthSource sorted_of = [&](int k, std::size_t i) {
        const std::string path = sorted_path(job.dir, of.pass, k);
        return in_phase(kExitInput, path,
                        [&] { return SortedDepthsFile(path, key, of.pass, k).values(i); });
    };
    const TilePass target = texel_pass_after(of.pass);
    const std::string depth_dir = (fs::path(job.dir) / name_of(of.pass)).string();
    std::optional<std::vector<double>> thresholds;  // at the first part made: none may be
    // The thresholds one job of the pass merged, left for the others: each would merge the
    // same files (3.7 s of a 10 s job at level 11 in 16 tiles). A file of another run, or a
    // damaged one, is refused by name.
    const std::string thresholds_path =
        (fs::path(job.dir) / name_of(target) / "seed-thresholds").string();
    const auto seed_thresholds = [&](const DepthTile& tile) {
        if (fs::exists(thresholds_path))
            return timed_stage(progress, "reading the seeds' thresholds", [&] {
                return read_binary_file(thresholds_path, [&](std::istream& in) {
                    return read_seed_thresholds(in, key, target, of.orientations.size());
                });
            });
        std::vector<double> merged = timed_stage(progress, "the seeds' thresholds", [&] {
            return in_phase(kExitInput, depth_dir,
                            [&] { return texel_thresholds_merged(tile, o.params, of, sorted_of); });
        });
        OutputSet outputs(OutputLinks::Refuse);
        outputs.add(thresholds_path,
                    [&](std::ostream& out) { write_seed_thresholds(out, key, target, merged); });
        outputs.commit();
        return merged;
    };
    WholeMeshFallback whole;
    make_parts(o, job, key, target, chosen, progress, [&](int b) {
        std::optional<TilePart> part;
        {
            DepthTile tile = read_tile(job.dir, key, b, progress);
            if (!thresholds) thresholds = seed_thresholds(tile);
            std::vector<std::vector<double>> depths =
                timed_stage(progress, "the depths of tile " + std::to_string(b + 1), [&] {
                    return in_phase(kExitInput, depth_dir,
                                    [&] { return depths_in_tile(tile, o.params, of, part_of); });
                });
            // The tile's mesh is let go while the regions grow in a narrower cut of it, and
            // read again if they reach its edge.
            const auto read_mesh_again = [&] {
                return timed_stage(
                    progress, "reading the mesh of tile " + std::to_string(b + 1) + " again", [&] {
                        return read_tile_mesh_file(tile_mesh_path(job.dir, b), key, b).mesh.mesh;
                    });
            };
            part = in_phase(kExitProcessing, o.mesh, [&] {
                return texel_part_in_tile(std::move(tile), std::move(depths), *thresholds, o.params,
                                          of, read_mesh_again);
            });
        }
        if (part) return std::move(*part);
        return whole.part(o, job.dir, key, target, b, "a texel grows past the tile's halo",
                          progress);
    });
    // The job that ends the pass joins its texels for the jobs after it, which then read them
    // instead of each joining every part, even when they start together (a Slurm array). A job
    // that ends while a part is missing leaves that to a later one, or to the first job after
    // the pass (texels_joined_once).
    if (all_parts_exist(job.dir, target, o.tiles) &&
        !fs::exists(joined_texels_path(job.dir, target))) {
        whole = WholeMeshFallback{};  // the whole mesh, when a tile needed it, is not held beside
        texels_joined_once(job.dir, key, read_tile_numbers(job.dir, key, chosen.front()), o.params,
                           of, o.mesh,
                           target == TilePass::Texels ? "texels" : "texels without rims", progress);
    }
}

// Says that pass `pass` is not needed in this run, and why.
void note_not_needed(const SegmentRunOptions& o, TilePass pass, Progress& progress) {
    const char* why = !o.params.remove_rims    ? "--keep-rims"
                      : pass == TilePass::Rims ? "an orientation has no texel, so no texel is a rim"
                                               : "no detail is left out of a second smoothing";
    progress.note(o.mesh + ": pass " + name_of(pass) + " is not needed in this run (" + why +
                  "); nothing to do");
}

// Pass `target` of the chosen tiles from the tile meshes and the parts of the passes before,
// never the whole mesh (but for a texel that outgrows its tile). The later passes build on the
// texels, the rims and the second smoothing's texels, joined from their parts with the run's
// numbers that any tile carries.
void make_parts_from_tiles(const SegmentRunOptions& o, const TileJobOptions& job,
                           const std::string& key, TilePass target, const std::vector<int>& chosen,
                           Progress& progress) {
    set_current_input(o.mesh);
    const auto make = [&](auto&& part_of_tile) {
        make_parts(o, job, key, target, chosen, progress, [&](int b) {
            DepthTile tile = read_tile(job.dir, key, b, progress);
            return in_phase(kExitProcessing, o.mesh, [&] { return part_of_tile(std::move(tile)); });
        });
    };
    if (target == TilePass::Depth)
        return make([&](DepthTile tile) { return first_depth_part(std::move(tile), o.params); });
    if (target == TilePass::Texels)
        return make_texel_parts(o, job, key, chosen, first_depth_pass(o.params), progress);

    const DepthTile first = read_tile_numbers(job.dir, key, chosen.front());
    const auto joined = [&](const char* stage, TilePass pass, auto&& join) {
        require_parts(job.dir, pass, o.tiles, o.mesh);
        return timed_stage(progress, stage, [&] {
            return in_phase(kExitInput, (fs::path(job.dir) / name_of(pass)).string(), join);
        });
    };
    // The second smoothing's jobs learn from the rims parts alone, once the rims pass has made
    // them all, whether it has anything to do: the texels are joined (10-13 s at level 11, for
    // each of 32 jobs of sphere-1, which has no second smoothing) only when it has.
    const bool second_smoothing =
        target == TilePass::DepthWithoutRims || target == TilePass::TexelsWithoutRims;
    if (second_smoothing && all_parts_exist(job.dir, TilePass::Rims, o.tiles)) {
        const JoinedRims alone = joined("reading the rims", TilePass::Rims, [&] {
            return join_rims_alone(o.tiles, o.params, parts_of(job.dir, key, TilePass::Rims));
        });
        if (alone.second.orientations.empty()) return note_not_needed(o, target, progress);
    }
    const DepthPassOf first_pass = first_depth_pass(o.params);
    JoinedTexels texels =
        texels_joined_once(job.dir, key, first, o.params, first_pass, o.mesh, "texels", progress);
    const bool has_rims = rims_needed(texels, o.params);
    if (target != TilePass::Features && !has_rims) return note_not_needed(o, target, progress);
    if (target == TilePass::Rims)
        return make([&](DepthTile tile) { return rims_part(std::move(tile), texels, o.params); });

    JoinedRims rims;  // none: no second smoothing
    if (has_rims)
        rims = joined("joining the rims", TilePass::Rims, [&] {
            return join_rims(first, texels, o.params, parts_of(job.dir, key, TilePass::Rims));
        });
    const DepthPassOf& second_pass = rims.second;
    if (target != TilePass::Features && second_pass.orientations.empty())
        return note_not_needed(o, target, progress);
    if (target == TilePass::DepthWithoutRims)
        return make([&](DepthTile tile) {
            return depth_without_rims_part(std::move(tile), texels, rims, o.params);
        });
    if (target == TilePass::TexelsWithoutRims)
        return make_texel_parts(o, job, key, chosen, second_pass, progress);

    // The features: the segmentation's texels, and each orientation's depths from the last
    // depth pass that smoothed it.
    JoinedTexels second;
    if (!second_pass.orientations.empty())
        second = texels_joined_once(job.dir, key, first, o.params, second_pass, o.mesh,
                                    "texels without rims", progress);
    const std::vector<Texel> all =
        segmentation_texels(std::move(texels), std::move(second), rims, o.params);
    std::array<DepthSource, 2> depths;
    for (DetailOrientation d : {DetailOrientation::Positive, DetailOrientation::Negative}) {
        const std::vector<DetailOrientation>& again = second_pass.orientations;
        const DepthPassOf& pass =
            std::find(again.begin(), again.end(), d) != again.end() ? second_pass : first_pass;
        require_parts(job.dir, pass.pass, o.tiles, o.mesh);
        require_sorted(job.dir, pass.pass, o.tiles, o.mesh);
        depths[d == DetailOrientation::Positive ? 0 : 1] = {
            pass, parts_of(job.dir, key, pass.pass),
            greatest_depths(job.dir, key, pass.pass, o.tiles)};
    }
    WholeMeshFallback whole;
    make_parts(o, job, key, target, chosen, progress, [&](int b) {
        std::optional<TilePart> part;
        {
            DepthTile tile = read_tile(job.dir, key, b, progress);
            part = in_phase(kExitProcessing, o.mesh,
                            [&] { return features_part(std::move(tile), all, depths, o.params); });
        }
        if (part) return std::move(*part);
        return whole.part(o, job.dir, key, target, b,
                          "a texel and its curvature discs reach past the tile's halo", progress);
    });
}

}  // namespace

void check_tile_job_options(const TileJobOptions& job, int tiles) {
    if (job.dir_given && job.dir.empty())
        throw CliError(kExitUsage, "--tile-dir: the directory name is empty");
    const bool mesh_pass = job.pass == kMeshPass;
    if (job.pass_given && !mesh_pass) pass_named(job.pass);
    if (job.shard_given) parse_shard(job.shard);
    if (job.dir.empty()) {
        if (!job.pass.empty() || job.tile != 0 || !job.shard.empty())
            throw CliError(kExitUsage, "--pass, --tile and --shard need --tile-dir");
        return;
    }
    if (tiles < 1)
        throw CliError(kExitUsage, "--tile-dir needs --tiles N (the number of tiles, at least 1)");
    if (job.pass.empty() && (job.tile != 0 || !job.shard.empty()))
        throw CliError(kExitUsage, "--tile and --shard choose the tiles of a --pass");
    if (mesh_pass && (job.tile != 0 || !job.shard.empty()))
        throw CliError(kExitUsage,
                       "--pass mesh is one job for the whole mesh: no --tile or --shard");
    if (job.tile != 0 && !job.shard.empty())
        throw CliError(kExitUsage, "give --tile or --shard, not both");
    if (job.tile < 0 || job.tile > tiles)
        throw CliError(kExitUsage, "--tile " + std::to_string(job.tile) +
                                       ": tiles are numbered 1 to " + std::to_string(tiles));
    if (!job.shard.empty()) parse_shard(job.shard);
}

void run_tile_pass(const SegmentRunOptions& o, const TileJobOptions& job, Progress& progress) {
    if (job.pass == kMeshPass) return run_mesh_pass(o, job.dir, progress);
    const TilePass target = pass_named(job.pass);
    // With --keep-rims the options alone tell that the rims and the second smoothing are
    // skipped: a job of those passes reads nothing.
    const bool after_rims = target == TilePass::Rims || target == TilePass::DepthWithoutRims ||
                            target == TilePass::TexelsWithoutRims;
    if (after_rims && !o.params.remove_rims) return note_not_needed(o, target, progress);
    const std::string key = run_key(o);
    const std::vector<int> chosen = chosen_tiles(job, o.tiles);
    // The passes need no more of the whole mesh than their tiles: when the mesh pass has cut
    // them, a job reads its tiles alone.
    const bool cut = std::all_of(chosen.begin(), chosen.end(),
                                 [&](int b) { return fs::exists(tile_mesh_path(job.dir, b)); });
    if (chosen.empty())  // a shard past the last tile: nothing to read or make
        return make_parts(o, job, key, target, chosen, progress,
                          [](int) -> TilePart { throw std::logic_error("no tile is chosen"); });
    if (cut) return make_parts_from_tiles(o, job, key, target, chosen, progress);
    const std::unique_ptr<JoinedRun> joined = join_passes(o, job.dir, key, target, progress);
    const TiledSegmentation& run = *joined->run;
    if (run.pass() != target) return note_not_needed(o, target, progress);
    make_parts(o, job, key, target, chosen, progress, [&](int b) {
        return in_phase(kExitProcessing, o.mesh, [&] { return run.run_tile(b); });
    });
}

SegmentRun merge_tile_parts(const SegmentRunOptions& o, Progress& progress) {
    const std::string key = run_key(o);
    const std::string path = mesh_path(o.tile_dir);
    SegmentRun out;
    // Kept for the outputs, the run holds none of the depth maps' arrays, the metrics'
    // arrays, the curvature field or the face labels (write_segmentation_ply makes them from
    // the texels).
    std::optional<TiledSegmentation> run;
    if (!fs::exists(path)) {
        // No mesh pass: the mesh is read and repaired whole, and its faces written from memory.
        out.input = load_mesh(o.mesh, progress, o.tiles);
        in_phase(kExitProcessing, o.mesh, [&] {
            run.emplace(out.input.repaired.mesh, o.params, o.tiles, TiledResult::Outputs);
        });
    } else {
        // The faces stay in mesh.part, read a block at a time, and the positions go to a
        // scratch file read through its mapping: the join holds the texels, not the 12 bytes a
        // face of the faces, the 8 of their labels and the 12 of the positions. A directory
        // the join may only read leaves it the positions to hold.
        OutlinedTileMesh outlined =
            outline_tile_mesh(o, o.tile_dir, key, progress, OutlinePositions::OnDiskOrHeld);
        note_repair(o, outlined.input.repaired, progress);
        out.input = std::move(outlined.input);
        out.joined_faces = outlined.faces;
        out.joined_positions = outlined.positions;
        // The extent the mesh job measured, when it left it: measuring again reads the
        // positions in the order of the faces.
        const std::string extent_path = mesh_extent_path(o.tile_dir);
        MeshMetrics extent;
        if (fs::exists(extent_path)) {
            extent = read_binary_file(extent_path,
                                      [&](std::istream& in) { return read_mesh_extent(in, key); });
            if (static_cast<std::size_t>(extent.num_faces) != outlined.num_faces ||
                static_cast<std::size_t>(extent.num_vertices) != out.positions().size())
                throw CliError(kExitInput, extent_path + ": the extent of a mesh of " +
                                               std::to_string(extent.num_vertices) +
                                               " vertices and " + std::to_string(extent.num_faces) +
                                               " faces, not of " + path);
        } else {
            extent =
                measure_extent(out.positions(), outlined.faces, outlined.num_faces, path, progress);
        }
        const MeshOutline mesh = outline_of(out.positions(), outlined.faces, extent);
        in_phase(kExitProcessing, o.mesh, [&] { run.emplace(mesh, o.params, o.tiles); });
    }
    join_parts_until(*run, o.tile_dir, key, TilePass::Done, o.mesh, progress,
                     JoinFrom::WhatJobsLeft);
    out.seg = std::move(*run).result();
    return out;
}

}  // namespace geotex::cli
