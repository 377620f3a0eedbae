#pragma once
// The lab frame and the angle conventions as named constants and helpers; docs/conventions.md
// states them (and the s/p frame, Jones, phase, conoscopic and exposure conventions) once.
//   x east (right in the image), y north (up), z toward the observer; light travels +z.
//   Angles are counter-clockwise as the observer sees them (looking down −z), from +x.
#include <cmath>
#include <numbers>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/base/units.h"

namespace pmsim {

inline constexpr glm::dvec3 kLabEast{1.0, 0.0, 0.0};
inline constexpr glm::dvec3 kLabNorth{0.0, 1.0, 0.0};
// The microscope axis, pointing toward the observer: the direction light travels (the axial ray).
inline constexpr glm::dvec3 kLightDirection{0.0, 0.0, 1.0};

// Transmission direction, in the lab (x, y) plane, of a polarizer or analyzer at angle_deg
// (polarizer_deg 0 = E–W, analyzer_deg 90 = N–S).
inline glm::dvec2 polarizer_direction(double angle_deg) {
  const double a = radians(angle_deg);
  return {std::cos(a), std::sin(a)};
}

// The accessory slot at 45°: every compensator has its slow direction NE–SW and its fast one
// NW–SE. √½ = √2/2 exactly in binary (halving is exact), so these equal std::sqrt(0.5).
inline constexpr glm::dvec3 kSlotSlow{0.5 * std::numbers::sqrt2, 0.5 * std::numbers::sqrt2, 0.0};
inline constexpr glm::dvec3 kSlotFast{-0.5 * std::numbers::sqrt2, 0.5 * std::numbers::sqrt2, 0.0};

// The stage turned by stage_rad counter-clockwise (seen by the observer) about lab z, as a
// rotation matrix (glm is column-major: the columns are the images of x̂, ŷ, ẑ).
inline glm::dmat3 stage_rotation(double stage_rad) {
  const double c = std::cos(stage_rad), s = std::sin(stage_rad);
  return glm::dmat3(glm::dvec3(c, s, 0), glm::dvec3(-s, c, 0), kLightDirection);
}

}  // namespace pmsim
