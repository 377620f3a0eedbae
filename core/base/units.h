#pragma once
// Angle units and π, one spelling for every module.
#include <numbers>

namespace pmsim {

inline constexpr double kPi = std::numbers::pi;

// The factor is glm::radians's (π/180 written to 32 digits, which rounds to the same double as
// std::numbers::pi / 180): replacing one by the other changes no bit of any result.
constexpr double radians(double deg) { return deg * 0.01745329251994329576923690768489; }
constexpr double degrees(double rad) { return rad * 57.295779513082320876798154814105; }

}  // namespace pmsim
