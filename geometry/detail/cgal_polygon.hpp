#pragma once
/// The two CGAL calls of repair_soup behind geotex types, so that mesh_repair.cpp does not
/// include CGAL.

#include <Eigen/Core>
#include <array>
#include <vector>

namespace geotex::detail {

/// Triangulates a closed polygon given by its corners in order (at least 3) with
/// CGAL::Polygon_mesh_processing::triangulate_hole_polyline. Returns #ring - 2 triangles
/// as indices into `ring`, each ordered like the ring (so they keep its orientation), or
/// an empty vector when CGAL finds no triangulation. Above 100 corners, only a planar ring
/// that does not cross itself is triangulated (CGAL's searches are cubic in the corners).
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Eigen::Vector3d>& ring);

/// True when the three points lie exactly on one line (exact predicate; equal points count
/// as collinear).
bool collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace geotex::detail
