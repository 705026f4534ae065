#pragma once
// The segmentation part shared by `segment` and `annotate`: its options, its run from a
// mesh file, and its outputs.

#include <array>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/mesh_input.hpp"
#include "cli/output.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/scale_levels.hpp"
#include "geometry/scale_series.hpp"
#include "geometry/scratch_file.hpp"
#include "geometry/segmentation.hpp"

// CLI11 declared only: it is header-only, and every source that includes it pays seconds of
// compile time (15 s under the sanitizers) even when it uses none of it; the sources that
// register options include <CLI/CLI.hpp> themselves.
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace geotex::cli {

struct SegmentRunOptions {
    SegmentationParams params;
    std::string mesh;
    std::string scale_text;    ///< --scale as given: a fraction, or "auto"
    double scale = 0;          ///< --scale as a number (check_segmentation_options)
    bool auto_scale = false;   ///< --scale auto: chosen per mesh by choose_auto_scale
    ScaleSeriesParams series;  ///< the series --scale auto looks at (docs/scales.md)
    bool levels = false;       ///< --levels: every plateau's scale as a level (segment_levels)
    double radius = 0;
    bool vertex_mean = false;
    bool keep_rims = false;
    /// --tiles N: segment N spatial tiles one at a time (run_tiled_segmentation,
    /// tiled_segmentation.hpp), the same result in less memory; 0: the whole mesh at once
    int tiles = 0;
    /// --tile-dir DIR with --tiles: join the parts that jobs of each pass wrote there
    /// (tile_jobs.hpp) instead of running the passes
    std::string tile_dir;
    const CLI::Option* scale_option = nullptr;  ///< to tell "--scale 0" from no --scale
    const CLI::Option* radius_option = nullptr;
};

/// Adds the MESH positional (unless `with_mesh` is false) and the options of the pipeline
/// (--scale and --radius unless `with_scale` is false, --orientation, --smoothing, ...) to a
/// subcommand.
void add_segmentation_options(CLI::App& sub, SegmentRunOptions& o, bool with_mesh = true,
                              bool with_scale = true);

/// Fills the parameters from the flags (--vertex-mean, --keep-rims) that are not the scale.
void apply_segmentation_flags(SegmentRunOptions& o);

struct SegmentRun {
    InputMesh input;
    Segmentation seg;
    std::optional<ScaleChoice> scale_choice;  ///< with --scale auto: how the scale was chosen
    std::vector<DetailLevel> levels;          ///< with --levels: fine to coarse, `seg` is main
    /// The join of a tiled run (--tile-dir, merge_tile_parts) leaves `seg` without face arrays
    /// and, when DIR/mesh.part is there, input.repaired.mesh without faces or positions: the
    /// faces stay in the file, and this reads them a block at a time (write_segmentation_ply).
    FaceBlockReader joined_faces;
    /// With joined_faces, the positions, copied from mesh.part to a scratch file in DIR and
    /// read through its mapping, whose pages the system takes back when memory is short.
    std::shared_ptr<PositionFile> joined_positions;

    /// The mesh's positions: joined_positions' when there are any, else input's.
    PositionSpan positions() const {
        return joined_positions ? joined_positions->positions()
                                : PositionSpan(input.repaired.mesh.positions);
    }
};

/// Checks --scale and --radius and fills the parameters from them; CliError kExitUsage.
void check_segmentation_options(SegmentRunOptions& o);

/// Checks the options (check_segmentation_options), reads and repairs the mesh, runs the
/// pipeline, reports diagnostics and warns when nothing is salient.
SegmentRun run_segmentation_stage(SegmentRunOptions& o, Progress& progress);

/// For --scale auto: segments the mesh over the series (progress on stderr), reports the
/// choice, and sets o.params.radius_rel to the chosen scale. Returns the choice.
ScaleChoice choose_auto_scale(SegmentRunOptions& o, const InputMesh& input, Progress& progress);

/// For --levels: segments the mesh at the other levels of the choice (progress on stderr) and
/// links each level's texels to the next coarser level's; `main` is the segmentation at the
/// chosen scale.
std::vector<DetailLevel> segment_other_levels(const SegmentRunOptions& o, const InputMesh& input,
                                              const ScaleChoice& choice, const Segmentation& main,
                                              Progress& progress);

/// Runs the pipeline on a loaded mesh (options already checked) and reports it.
Segmentation segment_mesh(const SegmentRunOptions& o, const InputMesh& input, Progress& progress);

/// The segmentation's diagnostics on stderr, and a warning when nothing is salient.
void report_segmentation(const SegmentRunOptions& o, const Segmentation& seg, Progress& progress);

/// Face attributes of the segmentation PLY: texel, texture, red, green, blue. They read
/// `seg`'s face arrays, which must outlive them.
std::vector<FaceAttribute> segmentation_attributes(const Segmentation& seg);

/// The segmentation PLY of `run`: its mesh with segmentation_attributes and `more` (#F each,
/// --levels'). A tiled run's join (no seg.face_texel) is written a block of faces at a time,
/// from run.joined_faces or the mesh, with the labels made from the texels (FaceLabelCursor),
/// and takes no `more`.
void write_segmentation_ply(std::ostream& out, const SegmentRun& run,
                            const std::vector<FaceAttribute>& more, const PlyWriteOptions& options);

/// "MESH: N texels in M textures ..." and one line per texture, on stdout.
void print_texture_summary(const std::string& mesh, const Segmentation& seg, OrientationMode mode);

}  // namespace geotex::cli
