#pragma once
// Angle constants and conversions, one definition for the whole tree. The model keeps
// angles in degrees in its data (names end in _deg) and in radians inside the maths:
//   x_rad = x_deg * kDeg = degToRad(x_deg),   x_deg = x_rad / kDeg = radToDeg(x_rad).
#include <numbers>

namespace fovea {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = kPi / 180.0;  // one degree in radians

constexpr double degToRad(double deg) {
  return deg * kPi / 180.0;
}
constexpr double radToDeg(double rad) {
  return rad * 180.0 / kPi;
}

}  // namespace fovea
