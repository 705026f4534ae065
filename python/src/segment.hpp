#pragma once
// The result of geotex.segment, which geotex.annotate also takes (annotate.cpp).

#include <optional>
#include <string>
#include <vector>

#include "geometry/mesh_repair.hpp"
#include "geometry/scale_levels.hpp"
#include "geometry/scale_series.hpp"
#include "geometry/segmentation.hpp"
#include "pipeline/report_json.hpp"

namespace geotex::python {

/// What geotex.segment returns (Python class geotex.Segmentation): the repaired mesh the
/// labels refer to and the segmentation. Python owns it; every array it hands out is a view
/// that keeps it alive.
struct SegmentationResult {
    MeshRepairResult input;
    Segmentation seg;
    SegmentationParams params;  ///< as checked, the command's for the same options
    OrientationMode mode = OrientationMode::Positive;
    /// scale="auto": the series and the scale chosen from it (the command's --scale auto).
    std::optional<ScaleChoice> scale_choice;
    /// levels=True: every level, fine to coarse, the main one being `seg` (--levels).
    std::vector<DetailLevel> levels;
    /// The file read (annotate_file's path as given, and its MeshFile::format); both empty
    /// for arrays.
    std::string file, format;

    /// The "input" of the JSON report: the file and its format, or for arrays `array_name`
    /// and "ply-binary-le" (the PLY array_identity digests); the repair counts either way.
    ReportInput report_input(const std::string& array_name = "mesh.ply") const {
        if (file.empty()) return {array_name, "ply-binary-le", input.report};
        return {file, format, input.report};
    }
};

}  // namespace geotex::python
