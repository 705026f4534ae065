#pragma once
/// The JSON report of `geotex segment --json` and `geotex annotate --json`, in one call, so
/// that a library caller gets the bytes the command writes:
///
///   MeshFile file = read_mesh_file("vase.ply");
///   make_unit_frame(file.soup.positions);
///   const MeshRepairResult repaired = repair_soup(std::move(file.soup));
///   const Annotation a = annotate(repaired.mesh, file_identity("vase.ply", file.format),
///                                 dictionary, options);
///   std::cout << report_text(annotation_report(a, {"vase.ply", file.format, repaired.report}));
///
/// Keys come in one fixed order and numbers in their shortest exact form, so the same run
/// gives the same bytes (README.md, `geotex segment` and `geotex annotate`, --json).

#include <nlohmann/json.hpp>
#include <string>

#include "geometry/mesh_repair.hpp"
#include "geometry/segmentation.hpp"
#include "pipeline/annotate.hpp"

namespace geotex {

/// What the report's "input" says of the mesh that was read.
struct ReportInput {
    std::string file;         ///< the mesh's path as the command was given it (MESH)
    std::string format;       ///< MeshFile::format: "ply-ascii", "off", "obj", ...
    MeshRepairReport repair;  ///< what repair_soup did to the file's polygons
};

/// The report of `geotex segment --json`: "geotex" (version, document "segmentation",
/// schema 1), "input" (of `input`), "parameters" (parameters_json of `params` at the radius
/// used), "mesh", "smoothing", "depth" (one entry per orientation extracted), "features" (the
/// feature ids), "texels" (per texel its orientation, texture, faces, seed, threshold and
/// features, null where undefined), "textures" (orientation, colour, texels) and
/// "diagnostics". `segmentation` must be run_segmentation's for `params` (or read back from a
/// geometry cache made with them). With `scale_choice` (`--scale auto`), "scale_choice" follows
/// "parameters": the series as scale_series_json writes it, with "chosen" (the scale, as in
/// "parameters") and "stable". Throws InvalidInput when its sizes disagree (a depth map
/// missing for an orientation run, a feature table or texel_texture not one row per texel).
/// With `levels` (`--levels`, segment_levels with `segmentation` as main), "levels" comes
/// last: per level (fine to coarse) "level", "scale", "radius", "main", "texel_count",
/// "texture_count" and "part_of" (per texel, the next coarser level's texel it lies on, or
/// null); the levels but the main one also have "texels" and "textures" as above.
nlohmann::ordered_json segmentation_report(const Segmentation& segmentation,
                                           const SegmentationParams& params,
                                           const ReportInput& input,
                                           const ScaleChoice* scale_choice = nullptr,
                                           const std::vector<DetailLevel>* levels = nullptr);

/// The report of `geotex annotate --json`: segmentation_report of the annotation's
/// segmentation and options, and "annotation": the dictionary (id, version, source, sha256),
/// the "choice" options and per texture its chosen and withheld concepts (feature, concept,
/// label in the options' label_language, facet, value, significance, agreement, stability)
/// and every feature's value, significance, rank and concept; with the annotation's levels,
/// "levels" as segmentation_report's, whose other levels also have "annotation" (their
/// textures' words as "annotation"'s "textures"). Throws InvalidInput as
/// segmentation_report does, and when the annotation has no dictionary.
nlohmann::ordered_json annotation_report(const Annotation& annotation, const ReportInput& input);

/// The text of a report as the command writes it: two-space indentation, UTF-8, and a final
/// newline.
std::string report_text(const nlohmann::ordered_json& report);

/// The report's "scale_choice" (`--scale auto`): the series as scale_series_json writes it,
/// with "chosen" (the scale taken) and "stable".
nlohmann::ordered_json scale_choice_json(const ScaleChoice& choice);

/// `x` as a JSON number, or null when it is not finite (JSON has no NaN nor infinity): how
/// every report writes an undefined value.
nlohmann::ordered_json number_or_null(double x);

}  // namespace geotex
