#pragma once
/// Discrete curvatures per vertex (Meyer, Desbrun, Schröder & Barr 2003): Gaussian curvature
/// from the angle defect, mean curvature from the cotangent Laplacian, both over the mixed
/// Voronoi area; principal curvatures, Koenderink's shape index and curvedness from them.

#include <vector>

#include "geometry/mesh.hpp"
#include "geometry/topology.hpp"

namespace geotex {

/// Per-vertex curvature, in the units of the mesh (1/length^2 for Gaussian, 1/length for
/// mean and curvedness). NaN where undefined: boundary and isolated vertices (the angle
/// defect there measures the border, not the surface), and the shape index of flat
/// vertices (see CurvatureParams::flat_tolerance).
struct CurvatureField {
    std::vector<double> gaussian;     ///< #V, K = k1 k2
    std::vector<double> mean;         ///< #V, H = (k1 + k2) / 2, positive where convex
    std::vector<double> shape_index;  ///< #V, (2/pi) atan2(k1 + k2, k1 - k2), k1 >= k2:
                                      ///< +1 dome, 0.5 ridge, 0 saddle, -0.5 rut, -1 cup
    std::vector<double> curvedness;   ///< #V, sqrt((k1^2 + k2^2) / 2)
};

struct CurvatureParams {
    double flat_tolerance = 1e-9;  ///< the shape index is undefined where curvedness times
                                   ///< sqrt(vertex area) is below this (dimensionless: the
                                   ///< surface turns by less than this angle across a vertex)
};

/// Curvatures of every vertex, with `vertex_normal` (unit, consistently oriented) giving the
/// sign of the mean curvature. Parallel over vertices.
CurvatureField make_curvature(const Mesh& mesh, const MeshTopology& topology,
                              const std::vector<Eigen::Vector3d>& vertex_normal,
                              const CurvatureParams& params = {});

}  // namespace geotex
