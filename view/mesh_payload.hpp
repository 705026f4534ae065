#pragma once
/// GTXM, the binary mesh the workbench's page draws (view/README.md, "GTXM"): positions,
/// triangles and per-triangle texel, texture and depth in little-endian arrays that the page
/// hands to WebGL without parsing, instead of megabytes of JSON.

#include <string>
#include <vector>

#include "geometry/mesh_io.hpp"

namespace geotex::view {

/// Version written after the magic "GTXM".
constexpr unsigned kMeshPayloadVersion = 1;

/// The integer face property `property` (`texel`, `texture`) of each polygon, -1 for every
/// polygon when the file has no such property. Throws InvalidInput (naming `name`) when a
/// value is not an integer of -1 or more.
std::vector<int> face_property_ids(const MeshFile& file, const char* property,
                                   const std::string& name);

/// The GTXM bytes of a segmentation PLY as read_mesh_file gives it: its polygons split into
/// fans (triangle_fans), each triangle with its polygon's `texel` and `texture` face
/// properties (-1 when the file has no such property) and `texel_depth[texel]` as depth (NaN
/// for no texel). texel_depth: #texels, the texels' depth_mean from the report. Throws
/// InvalidInput (naming `name`) when a texel or texture value is not an integer >= -1, a texel
/// is out of range of texel_depth, a vertex index is out of range or a coordinate is not
/// finite as a float, or the counts exceed the format's 32 bits.
std::string make_mesh_payload(const MeshFile& segmentation, const std::vector<double>& texel_depth,
                              const std::string& name);

}  // namespace geotex::view
