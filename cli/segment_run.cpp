#include "cli/segment_run.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>

#include "cli/tile_jobs.hpp"
#include "geometry/tiled_segmentation.hpp"
#include "pipeline/texture_colour.hpp"

namespace geotex::cli {

namespace {

/// An option whose value is one of the names of the enum's table (any case), shown as
/// "a|b|c" in the table's order, with the target's value as the default. CheckedTransformer
/// alone also accepts the enum's underlying numbers ("--orientation 2"), so an IsMember check
/// on the names runs first (transforms run last-added first).
template <class T, std::size_t N>
void add_named_option(CLI::App& sub, const std::string& flag, T& target,
                      const std::array<std::pair<const char*, T>, N>& table,
                      const std::string& help) {
    std::map<std::string, T> names;
    std::vector<std::string> keys;
    std::string type_name;
    for (const auto& [name, value] : table) {
        names.emplace(name, value);
        keys.push_back(name);
        type_name += (type_name.empty() ? "" : "|") + std::string(name);
    }
    sub.add_option(flag, target, help)
        ->transform(CLI::CheckedTransformer(names, CLI::ignore_case).description(""))
        ->transform(CLI::IsMember(keys, CLI::ignore_case).description(""))
        ->type_name(type_name)
        ->default_str(name_in(table, target));
}

}  // namespace

void add_segmentation_options(CLI::App& sub, SegmentRunOptions& o, bool with_mesh,
                              bool with_scale) {
    if (with_mesh)
        sub.add_option("mesh", o.mesh, "Input mesh: .ply (ASCII or binary), .off, .obj or .stl")
            ->required();
    if (with_scale) {
        o.scale_option = sub.add_option("-s,--scale", o.scale_text,
                                        "Scale r as a fraction of the largest bounding-box side, "
                                        "in (0, 1) (paper: 0.04), or auto: the best stable "
                                        "scale of `geotex scales` (docs/scales.md)")
                             ->type_name("F|auto");
        o.radius_option =
            sub.add_option("-r,--radius", o.radius, "Scale r in mesh units (instead of --scale)");
        sub.add_flag("--levels", o.levels,
                     "With --scale auto: every stable scale as a level of detail (the "
                     "recommended scale of each plateau), each segmented, and each texel linked "
                     "to the coarser texel it lies on (docs/scales.md)");
    }
    add_named_option(
        sub, "--orientation", o.params.orientation, kOrientationModeNames,
        "Details above the surface (positive), below it (negative: engravings), or both");
    add_named_option(
        sub, "--smoothing", o.params.smoothing, kSmoothingMethodNames,
        "twicing: bias-corrected disc mean (a sphere has zero depth); mean: the paper's eq. 1");
    add_named_option(
        sub, "--disc", o.params.disc, kDiscModeNames,
        "Disc means: exact walks every disc; fast walks discs about r/4 apart and interpolates "
        "(cost independent of r; on sphere-1 the depth moves by 0.3% of the detail height on "
        "average); auto: fast where a disc holds 400 vertices or more");
    sub.add_option("--curvature-scale", o.params.curvature_scale,
                   "Curvature features from a quadric fitted over discs of this fraction of r "
                   "(robust to sampling noise); 0: the paper's one-ring operators")
        ->check(CLI::Range(0.0, 1.0));
    sub.add_flag("--vertex-mean", o.vertex_mean,
                 "Plain vertex mean in the discs (paper eq. 1) instead of area weights");
    sub.add_flag(
        "--keep-rims", o.keep_rims,
        "One smoothing, as the paper: a detail of the other orientation then raises a rim of "
        "spurious texels around it (default: smooth again without those details, docs/rims.md)");
    sub.add_option("--merge-overlap", o.params.merge_overlap,
                   "Merge touching regions whose depth intervals mu +- sigma overlap by this "
                   "fraction of the narrower")
        ->check(CLI::Range(0.0, 1.0));
    sub.add_option("--min-depth", o.params.min_depth_rel,
                   "Depth below this fraction of r is never salient")
        ->check(CLI::Range(0.0, 1.0));
    sub.add_option("--min-faces", o.params.min_faces, "Drop texels with fewer faces")
        ->check(CLI::Range(1, 1000000));
    sub.add_option("--max-textures", o.params.clustering.max_clusters,
                   "Largest number of textures tried")
        ->check(CLI::Range(1, 100));
    sub.add_option("--cluster-landmarks", o.params.clustering.max_points,
                   "Cluster at most this many texels of an orientation, evenly spaced among "
                   "them; each other texel joins the texture of the one most like it. The "
                   "clustering's time grows as the cube of the texels it sees and its memory as "
                   "the square (2000: about 1.5 s; 5000: 40 s); 0: every texel")
        ->check(CLI::Range(0, 100000000))
        ->check(CLI::Validator(
            [](std::string& text) {
                return std::strtol(text.c_str(), nullptr, 10) == 1
                           ? std::string("must be 0 (every texel) or at least 2")
                           : std::string();
            },
            "", ""));
}

void check_segmentation_options(SegmentRunOptions& o) {
    const bool has_scale = o.scale_option != nullptr ? o.scale_option->count() > 0
                                                     : !o.scale_text.empty() || o.scale != 0;
    const bool has_radius =
        o.radius_option != nullptr ? o.radius_option->count() > 0 : o.radius != 0;
    if (has_scale == has_radius)
        throw CliError(kExitUsage,
                       "give exactly one of --scale (fraction of the largest bounding-box side, "
                       "or auto) or --radius (mesh units)");
    o.auto_scale = has_scale && o.scale_text == "auto";
    if (has_scale && !o.auto_scale && !o.scale_text.empty()) {
        // strtod reads "nan", "inf" and hex too; the range check below refuses what is not a
        // fraction, and the whole text must be the number.
        const char* begin = o.scale_text.c_str();
        char* end = nullptr;
        errno = 0;
        o.scale = std::strtod(begin, &end);
        if (end == begin || *end != '\0')
            throw CliError(kExitUsage,
                           "--scale: '" + o.scale_text + "' is neither a number nor auto");
        // The words of every other floating option (refuse_non_finite_numbers in main.cpp).
        if (!std::isfinite(o.scale) || errno == ERANGE)
            throw CliError(kExitUsage, "--scale: not a finite number: '" + o.scale_text + "'");
    }
    if (o.tiles > 0 && o.auto_scale)
        throw CliError(kExitUsage,
                       "--tiles with --scale auto: the scale series segments the whole mesh at "
                       "every scale; give a --scale (geotex scales finds one) to segment in tiles");
    if (o.auto_scale) {
        try {
            scale_series_radii(o.series);
        } catch (const Error& e) {
            throw CliError(kExitUsage, std::string("--scale auto: ") + e.what());
        }
    }
    if (o.levels && !o.auto_scale)
        throw CliError(kExitUsage,
                       "--levels needs --scale auto: the levels are the stable scales of the "
                       "series");
    if (has_scale && !o.auto_scale && !(o.scale > 0 && o.scale < 1))
        throw CliError(
            kExitUsage,
            "--scale must be in (0, 1), a fraction of the largest bounding-box side (got " +
                std::to_string(o.scale) + ")");
    if (has_radius && !(o.radius > 0 && std::isfinite(o.radius)))
        throw CliError(kExitUsage, "--radius must be positive and finite (got " +
                                       std::to_string(o.radius) + ")");
    o.params.radius_rel = has_scale && !o.auto_scale ? o.scale : o.params.radius_rel;
    o.params.radius = has_radius ? o.radius : 0;
    apply_segmentation_flags(o);
}

ScaleChoice choose_auto_scale(SegmentRunOptions& o, const InputMesh& input, Progress& progress) {
    // The series may segment two scales at once: a note per scale instead of work lines.
    progress.end_work_lines();
    ScaleSeries series = in_phase(kExitProcessing, o.mesh, [&] {
        return timed_stage(progress, "scale series", [&] {
            return run_scale_series(
                input.repaired.mesh, o.params, o.series, [&](int index, int count, double rel) {
                    progress.note("--scale auto: scale " + std::to_string(index + 1) + "/" +
                                  std::to_string(count) + ": " + scale_percent(rel));
                });
        });
    });
    progress.begin_work_lines();
    for (const std::string& note : series.notes) progress.note(o.mesh + ": " + note);
    // Every scale skipped: the mesh is too coarse for the series, a matter of the input.
    ScaleChoice choice =
        in_phase(kExitInput, o.mesh, [&] { return choose_scale(std::move(series), o.series); });
    const ScaleStep& chosen = choice.series.steps[choice.chosen];
    char line[160];
    if (choice.stable)
        std::snprintf(line, sizeof line,
                      "--scale auto: %.4g, the best stable scale (%d of %d texels persist)",
                      chosen.radius_rel, chosen.persistent, chosen.texels);
    else
        std::snprintf(line, sizeof line,
                      "--scale auto: no stable scale; %.4g, the scale with the most persistent "
                      "texels (%d of %d)",
                      chosen.radius_rel, chosen.persistent, chosen.texels);
    progress.note(o.mesh + ": " + line);
    o.params.radius_rel = chosen.radius_rel;
    o.params.radius = 0;
    return choice;
}

void apply_segmentation_flags(SegmentRunOptions& o) {
    o.params.area_weighted = !o.vertex_mean;
    o.params.remove_rims = !o.keep_rims;
}

SegmentRun run_segmentation_stage(SegmentRunOptions& o, Progress& progress) {
    check_segmentation_options(o);
    if (!o.tile_dir.empty()) {
        SegmentRun run = merge_tile_parts(o, progress);
        report_segmentation(o, run.seg, progress);
        return run;
    }
    SegmentRun run{load_mesh(o.mesh, progress), {}, {}, {}, {}, {}};
    if (o.auto_scale) run.scale_choice = choose_auto_scale(o, run.input, progress);
    run.seg = segment_mesh(o, run.input, progress);
    if (o.levels)
        run.levels = segment_other_levels(o, run.input, *run.scale_choice, run.seg, progress);
    return run;
}

std::vector<DetailLevel> segment_other_levels(const SegmentRunOptions& o, const InputMesh& input,
                                              const ScaleChoice& choice, const Segmentation& main,
                                              Progress& progress) {
    std::vector<DetailLevel> levels = in_phase(kExitProcessing, o.mesh, [&] {
        return timed_stage(progress, "levels", [&] {
            return segment_levels(
                input.repaired.mesh, o.params, choice, main, [&](int index, int count, double rel) {
                    progress.note("--levels: level " + std::to_string(index + 1) + "/" +
                                  std::to_string(count) + ": " + scale_percent(rel));
                });
        });
    });
    std::string line = o.mesh + ": " + std::to_string(levels.size()) +
                       (levels.size() == 1 ? " level (no other stable scale):" : " levels:");
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const Segmentation& seg = level_segmentation(levels, k, main);
        int linked = 0;
        for (int c : levels[k].part_of) linked += c >= 0;
        line += (k == 0 ? " " : "; ") + scale_percent(levels[k].radius_rel) + " (" +
                std::to_string(seg.texels.size()) + " texels" +
                (k + 1 < levels.size() ? ", " + std::to_string(linked) + " on a coarser one" : "") +
                (levels[k].main ? ", main" : "") + ")";
    }
    progress.note(line);
    return levels;
}

Segmentation segment_mesh(const SegmentRunOptions& o, const InputMesh& input, Progress& progress) {
    Segmentation seg = in_phase(kExitProcessing, o.mesh, [&] {
        const StageObserver observer = [&](const StageEvent& e) { progress(e); };
        return o.tiles > 0
                   ? run_tiled_segmentation(input.repaired.mesh, o.params, o.tiles, observer)
                   : run_segmentation(input.repaired.mesh, o.params, observer);
    });
    report_segmentation(o, seg, progress);
    return seg;
}

void report_segmentation(const SegmentRunOptions& o, const Segmentation& seg, Progress& progress) {
    for (const auto& d : seg.diagnostics) progress.note(o.mesh + ": " + d.stage + ": " + d.message);
    if (seg.texels.empty()) {
        char radius[32];
        std::snprintf(radius, sizeof radius, "%.6g",
                      seg.radius);  // to_string would print 1e100 in full
        warn(o.mesh + ": no salient detail at radius " + radius +
             " (mesh units); the outputs list zero texels. Try another --scale or --orientation.");
    }
}

namespace {

// The attributes of segmentation_attributes over labels given apart from a segmentation.
std::vector<FaceAttribute> label_attributes(const std::vector<int>* face_texel,
                                            const std::vector<int>* face_texture,
                                            int num_textures) {
    std::vector<FaceAttribute> attributes(5);
    attributes[0] = {"texel", PlyScalarType::Int32, face_texel};
    attributes[1] = {"texture", PlyScalarType::Int32, face_texture};
    // The colour channels are the texture ids through each channel's table (from -1, the
    // background), so that a whole scan's faces are not held three more times.
    const char* names[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; ++c) {
        FaceAttribute& a = attributes[2 + c];
        a.name = names[c];
        a.type = PlyScalarType::UInt8;
        a.shared = face_texture;
        a.table_first = -1;
        for (int k = -1; k < num_textures; ++k) a.table.push_back(texture_colour(k)[c]);
    }
    return attributes;
}

}  // namespace

std::vector<FaceAttribute> segmentation_attributes(const Segmentation& seg) {
    return label_attributes(&seg.face_texel, &seg.face_texture, seg.num_textures);
}

void write_segmentation_ply(std::ostream& out, const SegmentRun& run,
                            const std::vector<FaceAttribute>& more,
                            const PlyWriteOptions& options) {
    const Mesh& mesh = run.input.repaired.mesh;
    if (!run.seg.face_texel.empty()) {
        std::vector<FaceAttribute> attributes = segmentation_attributes(run.seg);
        attributes.insert(attributes.end(), more.begin(), more.end());
        write_ply(out, mesh, attributes, options);
        return;
    }
    // A tiled run's join: labels from the texels, faces from mesh.part or the mesh.
    if (!more.empty()) throw std::logic_error("write_segmentation_ply: a join has no levels");
    const auto nf = static_cast<std::size_t>(run.seg.metrics.num_faces);
    const FaceBlockReader read_faces =
        run.joined_faces ? run.joined_faces : face_reader(mesh.faces);
    const PositionSpan positions = run.positions();
    std::vector<int> texel, texture;
    const std::vector<FaceAttribute> attributes =
        label_attributes(&texel, &texture, run.seg.num_textures);
    PlyWriter ply(out, positions.size(), nf, ply_fits_float(positions), attributes, options);
    ply.vertices(positions);
    FaceLabelCursor labels(run.seg);
    // A block at a time: the labels of a block and its faces take about 20 MB, where the
    // whole mesh's would take 20 bytes a face.
    for_each_face_block(read_faces, nf, [&](std::size_t first, const auto& faces) {
        labels.next(static_cast<int>(first), static_cast<int>(faces.size()), texel, texture);
        ply.faces(faces, attributes);
    });
    ply.finish();
}

void print_texture_summary(const std::string& mesh, const Segmentation& seg, OrientationMode mode) {
    std::printf("%s: %d texels in %d textures (radius %.6g mesh units, %s details)\n", mesh.c_str(),
                static_cast<int>(seg.texels.size()), seg.num_textures, seg.radius, name_of(mode));
    for (int k = 0; k < seg.num_textures; ++k) {
        int count = 0;
        long faces = 0;
        for (std::size_t i = 0; i < seg.texels.size(); ++i)
            if (seg.texel_texture[i] == k) {
                ++count;
                faces += static_cast<long>(seg.texels[i].faces.size());
            }
        std::printf("  texture %d (%s, %s): %d texels, %ld faces\n", k,
                    name_of(seg.texture_orientation[k]), hex_colour(texture_colour(k)).c_str(),
                    count, faces);
    }
}

}  // namespace geotex::cli
