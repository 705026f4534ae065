#pragma once
// Polygon soups and meshes for the tests of the repair, whole (test_mesh_repair.cpp) and in
// tiles (test_mesh_repair_tiles.cpp), and the check that two repairs of one soup agree.

#include <array>
#include <vector>

#include "geometry/mesh.hpp"
#include "geometry/mesh_repair.hpp"

namespace geotex::test {

using Polygons = std::vector<std::vector<int>>;

/// A soup of `positions` and `polygons`.
PolygonSoup make_soup(const std::vector<Eigen::Vector3d>& positions, const Polygons& polygons);
/// The mesh's triangles as a soup over its own vertices.
PolygonSoup make_soup(const Mesh& m);
/// `m` as a soup in which every triangle has its own three corners (as STL stores them), for
/// the repair to merge.
PolygonSoup own_corners_soup(const Mesh& m);

/// The triangle with its orientation reversed.
std::array<int, 3> flipped(const std::array<int, 3>& f);

/// Unit cube (times k), vertex x + 2y + 4z at (x, y, z).
std::vector<Eigen::Vector3d> cube_positions(double k = 1.0);
/// The cube's quads over cube_positions, counter-clockwise seen from outside.
extern const Polygons kCubeQuads;

/// A band of n quads around a circle of radius 3 that turns half over on the way.
PolygonSoup moebius_strip(int n);
/// Every step of the repair at once: an icosphere as a triangle soup with its own corners
/// (vertices to merge) and flipped faces, the cube as quads, a pentagon, a degenerate and a
/// duplicate face, and a third face on one of the cube's edges (non-manifold).
PolygonSoup every_step_soup();

/// `mesh` with each face reversed with probability `p` (a fixed seed).
Mesh randomly_flipped(Mesh mesh, double p, unsigned seed);
/// `mesh` moved by `by`.
Mesh moved(Mesh mesh, const Eigen::Vector3d& by);
/// Closed and open pieces of several sizes, some turned inside out or mostly reversed, with
/// duplicate faces (some reversed) and faces on a third side of an edge, spread over the
/// tiles of a repair in tiles.
Mesh mixed_scene();

/// Two repairs of one soup gave the same mesh, sources, report and notes.
void require_same_repair(const MeshRepairResult& a, const MeshRepairResult& b);

}  // namespace geotex::test
