#pragma once
/// The synthetic benchmark of paper §4.1: an icosphere displaced outward by a map of shapes
/// (big discs, small discs, squares, rectangles), with optional uniform noise, and its
/// ground truth.

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/mesh.hpp"

namespace geotex {

enum class ShapeKind { BigDisc, SmallDisc, Square, Rectangle };

/// Stable name of a kind ("big_disc", "small_disc", "square", "rectangle").
const char* shape_kind_name(ShapeKind kind);
/// Family of a kind: "disc" for both disc sizes, else the kind name.
const char* shape_kind_family(ShapeKind kind);

/// One shape drawn on the unit sphere.
struct SynthShape {
    int id = 0;
    ShapeKind kind = ShapeKind::BigDisc;
    Eigen::Vector3d center = Eigen::Vector3d::UnitZ();  ///< unit direction
    double angle = 0;                                   ///< rotation in the tangent plane, radians
    double half_length = 0;  ///< radius (discs) or half side along the shape axis,
                             ///< in sphere radii
    double half_width = 0;   ///< equal to half_length except for rectangles
    bool engraved = false;   ///< displaced inward (a negative detail)
};

struct SynthParams {
    int level = 7;                   ///< icosphere subdivision level (7: 327,680 faces)
    int num_big_discs = 17;          ///< sphere-1 of the paper: 17 big discs,
    int num_small_discs = 37;        ///< 37 small discs,
    int num_squares = 16;            ///< 16 squares
    int num_rectangles = 18;         ///< and 18 rectangles
    double displacement_rel = 0.02;  ///< largest displacement, fraction of the radius
    double edge_width_rel = 0.01;    ///< width of the grey ramp at shape edges, fraction of
                                     ///< the radius (the intermediate values of the map)
    double gap_rel = 0.12;           ///< least gap between shapes, fraction of the radius
    double noise_percent = 0;        ///< uniform radial noise in [-I, I] percent of the radius
    double engraved_fraction = 0;    ///< fraction of the shapes displaced inward instead
    std::uint64_t layout_seed = 1;   ///< placement of the shapes
    std::uint64_t noise_seed = 1;    ///< noise draw
};

struct SyntheticMesh {
    Mesh mesh;
    std::vector<SynthShape> shapes;   ///< id = index
    std::vector<double> vertex_grey;  ///< #V, the displacement map value in [0, 1]
    std::vector<int> vertex_shape;    ///< #V, the shape that gives vertex_grey, or -1
    std::vector<int> face_shape;      ///< #F, shape id or -1 (ground truth, paper §4.1:
                                      ///< mean grey of the face's vertices > 0.5)
};

/// Builds the synthetic sphere (radius 1). Deterministic for given seeds on every platform
/// (the random draws use std::mt19937_64, whose output the standard fixes, and our own
/// conversion to doubles). Throws InvalidInput on bad parameters or when the shapes do not
/// fit on the sphere.
SyntheticMesh make_synthetic_sphere(const SynthParams& params = {});

}  // namespace geotex
