#pragma once
/// Mathematical constants shared by the stages (C++17 has no std::numbers).

namespace geotex {

/// pi, to the precision of a double.
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace geotex
