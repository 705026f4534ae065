#pragma once
/// Icospheres: the regular subdivided icosahedron used by the synthetic benchmark and tests.

#include "geometry/mesh.hpp"

namespace geotex {

/// Unit sphere from an icosahedron subdivided `level` times (20 * 4^level faces: level 7
/// has 327,680), faces outward. Vertex order is deterministic. Throws InvalidInput for a
/// level outside [0, 11].
Mesh make_icosphere(int level);

}  // namespace geotex
