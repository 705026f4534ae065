#pragma once
/// Triangle mesh and polygon soup: the plain data every stage works on.

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, used by most stages
#include <array>
#include <vector>

namespace geotex {

/// Polygons as read from a file, before repair. Polygon p has the vertex indices
/// face_indices[face_offsets[p] .. face_offsets[p+1]).
struct PolygonSoup {
    std::vector<Eigen::Vector3d> positions;  ///< #P
    std::vector<int> face_offsets{0};        ///< #polygons + 1, starts with 0
    std::vector<int> face_indices;           ///< concatenated polygon vertex indices

    int num_polygons() const { return static_cast<int>(face_offsets.size()) - 1; }
};

/// The smallest axis-aligned box that holds `points`; empty (min above max) when there are none.
/// Written here once for the stages that each need the bounds of a mesh's positions.
inline Eigen::AlignedBox3d bounding_box(const std::vector<Eigen::Vector3d>& points) {
    Eigen::AlignedBox3d box;  // empty
    for (const Eigen::Vector3d& p : points) box.extend(p);
    return box;
}

/// A triangle mesh with contiguous indices (no deleted elements). Faces are oriented
/// consistently where the connectivity allows it (counter-clockwise seen from outside on
/// closed components).
struct Mesh {
    std::vector<Eigen::Vector3d> positions;  ///< #V
    std::vector<std::array<int, 3>> faces;   ///< #F

    int num_vertices() const { return static_cast<int>(positions.size()); }
    int num_faces() const { return static_cast<int>(faces.size()); }
};

}  // namespace geotex
