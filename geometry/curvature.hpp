#pragma once
/// Curvatures per vertex, at one of two scales. With no radius, the discrete operators of
/// Meyer, Desbrun, Schröder & Barr (2003) on the one-ring: Gaussian curvature from the angle
/// defect, mean curvature from the cotangent Laplacian, both over the mixed Voronoi area.
/// With a radius rho, the curvature at the vertex of a quadric height field fitted by
/// weighted least squares to the geodesic disc N_rho(v) (Cazals & Pouget's osculating
/// jets, order 2), which averages out noise of the sampling. Principal curvatures,
/// Koenderink's shape index and curvedness from either.

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
    /// rho, mesh units: > 0 fits a quadric over the geodesic disc N_rho(v) (a vertex whose
    /// disc holds fewer than 10 vertices falls back to the one-ring operators); 0 uses the
    /// one-ring operators everywhere. The one-ring turns noise of amplitude e on edges of
    /// length l into curvature errors of about e / l^2: on sphere-1 with noise I = 0.05 they
    /// exceed the curvature of the details, and the texture features drown.
    double radius = 0;
    /// #V flags, or empty for all: only flagged vertices get curvatures, the others NaN (the
    /// texture features need them only on the texels).
    std::vector<char> only;
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
