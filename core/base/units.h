#pragma once
// Angle units and π, one spelling for every module.
#include <cmath>
#include <numbers>

namespace pmsim {

inline constexpr double kPi = std::numbers::pi;

// deg·π/180 in this order of operations: the one every angle of a scene has always used, so
// results stay bit for bit where the code spelled it by hand.
constexpr double radians(double deg) { return deg * kPi / 180.0; }
constexpr double degrees(double rad) { return rad * 180.0 / kPi; }

// The direction of a line (not an arrow) in degrees, reduced to [0°, 180°).
inline double line_direction_deg(double deg) {
  double r = std::fmod(deg, 180.0);
  if (r < 0) r += 180.0;
  return r >= 180.0 ? r - 180.0 : r;
}

}  // namespace pmsim
