#pragma once
// Angle units and π, one spelling for every module.
#include <numbers>

namespace pmsim {

inline constexpr double kPi = std::numbers::pi;

// deg·π/180 in this order of operations: the one every angle of a scene has always used, so
// results stay bit for bit where the code spelled it by hand.
constexpr double radians(double deg) { return deg * kPi / 180.0; }
constexpr double degrees(double rad) { return rad * 180.0 / kPi; }

}  // namespace pmsim
