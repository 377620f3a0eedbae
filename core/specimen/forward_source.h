#pragma once
// What the two forward renderers (forward_plane_light.h: one image; forward_response.h: the
// specimen response) share of tracing from the condenser: a pass's rays, where a collected branch
// is imaged, and the tent splat that is a partition of unity over a grid of its period.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/specimen/jones_path.h"

namespace pmsim {

inline glm::dvec3 rotate_z(const glm::dvec3& v, double c, double s) {
  return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
}

template <class T>
void atomic_add(T& slot, T v) {
  std::atomic_ref<T>(slot).fetch_add(v, std::memory_order_relaxed);
}

// Where the focal plane z_air meets the line of a branch leaving the cover glass (the point the
// objective images it onto).
inline glm::dvec2 focal_point(const JonesExit& e, double z_air) {
  const glm::dvec3 q = e.point + ((z_air - e.point.z) / e.dir.z) * e.dir;
  return {q.x, q.y};
}

// One pass's ray: its direction and its λ's empty-stack shift and transmittance.
struct PassRay {
  glm::dvec3 dir{0.0, 0.0, 1.0};
  double wavelength_nm = 555.0;
  glm::dvec2 shift{0.0};  // focal point − start point in the empty stack
  double empty_t = 0.0;   // the empty stack's collected power for this ray
};

// A direction of the condenser's cone from two uniform numbers: sin θ = NA_c·√u1 (uniform in
// projected solid angle), azimuth 2π·u2.
inline glm::dvec3 cone_direction(double nac, double u1, double u2) {
  const double sin_t = nac * std::sqrt(u1), phi = 2.0 * 3.14159265358979323846 * u2;
  return {sin_t * std::cos(phi), sin_t * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - sin_t * sin_t))};
}

// Tent weights of radius r (grid units) of position f on the points of a ww × hh grid whose
// point (i, j) sits at (i + o, j + o): (1 − |Δx|/r)(1 − |Δy|/r). Over a grid of period r they sum
// to 1 at every point. `add(index, weight)`.
template <class Add>
void tent_splat(const glm::dvec2& f, int r, int ww, int hh, double o, const Add& add) {
  const double ux = f.x - o, uy = f.y - o;
  if (!(ux > -r && uy > -r && ux < ww - 1 + r && uy < hh - 1 + r)) return;
  const int x_lo = std::max(0, int(std::floor(ux)) - r + 1), x_hi = std::min(ww - 1, int(std::floor(ux)) + r);
  const int y_lo = std::max(0, int(std::floor(uy)) - r + 1), y_hi = std::min(hh - 1, int(std::floor(uy)) + r);
  for (int y = y_lo; y <= y_hi; ++y) {
    const double wy = 1.0 - std::abs(uy - y) / r;
    if (wy <= 0.0) continue;
    for (int x = x_lo; x <= x_hi; ++x) {
      const double wx = 1.0 - std::abs(ux - x) / r;
      if (wx > 0.0) add(std::size_t(y) * std::size_t(ww) + std::size_t(x), wx * wy);
    }
  }
}

}  // namespace pmsim
