#include "geometry/unit_frame.hpp"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/errors.hpp"

namespace geotex {

UnitFrame make_unit_frame(PositionSpan positions) {
    if (positions.empty()) throw InvalidInput("unit frame: the mesh has no vertex");
    // long double (x87: 64-bit mantissa, 15-bit exponent) holds hi - lo of any two finite
    // doubles exactly enough and without overflow.
    long double side = 0;
    for (int axis = 0; axis < 3; ++axis) {
        double lo = positions[0][axis], hi = lo;
        for (const auto& p : positions) {
            lo = std::fmin(lo, p[axis]);
            hi = std::fmax(hi, p[axis]);
        }
        side = std::fmax(side, static_cast<long double>(hi) - static_cast<long double>(lo));
    }
    char what[160];
    if (side == 0)
        throw InvalidInput("unit frame: the bounding box has zero size (all vertices coincide)");
    if (side > static_cast<long double>(DBL_MAX)) {
        std::snprintf(what, sizeof what,
                      "the largest bounding-box side (%.3Lg) is beyond the largest double (%.3g): "
                      "scale the mesh down",
                      side, DBL_MAX);
        throw InvalidInput(std::string("unit frame: ") + what);
    }
    if (side < static_cast<long double>(DBL_MIN)) {
        std::snprintf(what, sizeof what,
                      "the largest bounding-box side (%.3Lg) is below the smallest normal double "
                      "(%.3g): its unit scale would be infinite; scale the mesh up",
                      side, DBL_MIN);
        throw InvalidInput(std::string("unit frame: ") + what);
    }
    UnitFrame frame;
    frame.largest_side = static_cast<double>(side);
    frame.exponent = std::ilogb(frame.largest_side);
    return frame;
}

}  // namespace geotex
