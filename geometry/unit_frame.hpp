#pragma once
/// The power of two that brings a mesh to a unit size before any arithmetic, so that
/// squared lengths, areas and curvatures neither overflow nor underflow whatever the unit of
/// the file (a mesh at x1e300 or x1e-300 gives the texels it gives at x1).

#include <Eigen/Core>
#include <vector>

#include "geometry/mesh.hpp"

namespace geotex {

struct UnitFrame {
    double largest_side = 0;  ///< largest bounding-box side, mesh units (finite, normal)
    /// Multiplying a coordinate by 2^-exponent (exact: only the binary exponent changes)
    /// brings the largest side into [1, 2).
    int exponent = 0;
};

/// The frame of `positions`. The bounding box is measured in long double, so a side that
/// a double difference would overflow (coordinates of opposite signs near 1.8e308) is
/// still seen. Throws InvalidInput, saying what to do, when the largest side cannot be
/// represented as a double (above 1.8e308), is zero (all points coincide) or below the
/// smallest normal double, 2.2e-308 (its inverse, the unit scale written in the outputs,
/// would be infinite, and the coordinates have lost digits already). Requires finite
/// coordinates (the readers refuse others).
UnitFrame make_unit_frame(PositionSpan positions);

}  // namespace geotex
