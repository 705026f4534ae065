#pragma once
/// The picture of an object in the workbench's list: geotex's own renderer, the faces painted
/// with their texture's colour, as the segmentation PLY and the 3D view paint them.

#include <string>

#include "geometry/mesh_io.hpp"

namespace geotex::view {

/// Side of a thumbnail, in pixels.
constexpr int kThumbnailSide = 192;

/// PNG bytes of a kThumbnailSide square picture of a segmentation PLY (as read_mesh_file
/// gives it) seen from the iso view, each polygon in texture_colour of its `texture` property
/// (grey without one), texel outlines darkened. Deterministic. Throws InvalidInput (naming
/// `name`) when a texture or texel value is not an integer, or as render_mesh does.
std::string make_thumbnail(const MeshFile& segmentation, const std::string& name);

}  // namespace geotex::view
