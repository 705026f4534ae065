#pragma once
/// GTXM, the binary mesh the workbench's page draws (view/README.md, "GTXM"): positions,
/// triangles and per-triangle texel, texture and depth in little-endian arrays that the page
/// hands to WebGL without parsing, instead of megabytes of JSON.

#include <string>
#include <vector>

#include "geometry/mesh_io.hpp"

namespace geotex::view {

/// Version written after the magic "GTXM". 2: vertices split where texels meet, texture and
/// depth per texel instead of per face.
constexpr unsigned kMeshPayloadVersion = 2;

/// The integer face property `property` (`texel`, `texture`) of each polygon, -1 for every
/// polygon when the file has no such property. Throws InvalidInput (naming `name`) when a
/// value is not an integer of -1 or more.
std::vector<int> face_property_ids(const MeshFile& file, const char* property,
                                   const std::string& name);

/// The GTXM bytes (view/README.md) of a segmentation PLY as read_mesh_file gives it: its
/// polygons split into fans (as triangle_fans splits them), each triangle with its polygon's
/// `texel` face property (-1 when the file has none); per texel, its faces' `texture` and
/// `texel_depth[texel]`. A vertex shared by faces of different texels is copied, one copy per
/// texel (the file's vertices first, then the copies), so that a colour per vertex can be a
/// colour per texel and the page draws the indexed triangles as they are.
/// texel_depth: #texels, the texels' depth_mean from the report. Throws InvalidInput (naming
/// `name`) when a texel or texture value is not an integer >= -1, a texel is out of range of
/// texel_depth, the faces of a texel name different textures or a face in no texel names
/// one, a vertex index is out of range, a coordinate is not finite as a float, or the
/// counts exceed the format's 32 bits.
std::string make_mesh_payload(const MeshFile& segmentation, const std::vector<double>& texel_depth,
                              const std::string& name);

}  // namespace geotex::view
