#pragma once
// The band integral of an interference term: ∫_band w(λ)·cos(Φ0 + Φ1·(λ − λc)) dλ with the observer
// weight w linear across the band (W its integral, M = ∫ w·(λ − λc) dλ its first moment):
//   W·cos Φ0·sinc x − (6M/h)·sin Φ0·(sin x − x cos x)/x²,   x = Φ1·h/2.
// Exact for a phase linear across the band (integrate cos and t·cos termwise), so any number of
// orders inside one band averages out instead of aliasing into false colours.
#include <cmath>

#include <glm/vec3.hpp>

#include "core/render/fast_trig.h"

namespace pmsim {

inline glm::dvec3 oscillating_band(const glm::dvec3& W, const glm::dvec3& M6h, double phi0, double phi1,
                                   double h) {
  const double x = 0.5 * phi1 * h;
  double s0, c0;
  fast_sincos(phi0, s0, c0);
  double sinc, q;
  if (std::fabs(x) < 1e-3) {  // series: sinc = 1 − x²/6, (sin x − x cos x)/x² = x/3 − x³/30
    const double x2 = x * x;
    sinc = 1.0 - x2 / 6.0;
    q = x * (1.0 / 3.0 - x2 / 30.0);
  } else {
    double sx, cx;
    fast_sincos(x, sx, cx);
    sinc = sx / x;
    q = (sx - x * cx) / (x * x);
  }
  return W * (c0 * sinc) - M6h * (s0 * q);
}

}  // namespace pmsim
