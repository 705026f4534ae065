#pragma once
// The result of geotex.segment, which geotex.annotate also takes (annotate.cpp).

#include "geometry/mesh_repair.hpp"
#include "geometry/segmentation.hpp"

namespace geotex::python {

/// What geotex.segment returns (Python class geotex.Segmentation): the repaired mesh the
/// labels refer to and the segmentation. Python owns it; every array it hands out is a view
/// that keeps it alive.
struct SegmentationResult {
    MeshRepairResult input;
    Segmentation seg;
    SegmentationParams params;  ///< as checked, the command's for the same options
    OrientationMode mode = OrientationMode::Positive;
};

}  // namespace geotex::python
