#pragma once
// sin and cos together for the spectral inner loop, where libm's calls dominated the profile.
// Range reduction by k = round(x·2/π) with π/2 split in two parts (Cody–Waite), then the Taylor
// polynomials on |r| ≤ π/4 to degree 13/14 (truncation < 4e-13). Phases up to ~1e7 rad keep
// ≲1e-9 absolute error: enough for interference phases of 10 mm plates.
#include <cmath>
#include <cstdint>

namespace pmsim {

inline void fast_sincos(double x, double& s, double& c) {
  constexpr double two_over_pi = 0.63661977236758134308;
  constexpr double pio2_hi = 1.5707963267341256;        // first 33 bits of π/2
  constexpr double pio2_lo = 6.077100506506192e-11;      // π/2 − pio2_hi
  const double k = std::nearbyint(x * two_over_pi);
  const double r = (x - k * pio2_hi) - k * pio2_lo;
  const double r2 = r * r;
  const double sr =
      r * (1.0 + r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 +
           r2 * (-1.0 / 39916800 + r2 * (1.0 / 6227020800.0)))))));
  const double cr =
      1.0 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 +
           r2 * (-1.0 / 3628800 + r2 * (1.0 / 479001600.0 + r2 * (-1.0 / 87178291200.0)))))));
  const std::int64_t q = static_cast<std::int64_t>(k) & 3;
  switch (q) {
    case 0: s = sr; c = cr; break;
    case 1: s = cr; c = -sr; break;
    case 2: s = -sr; c = -cr; break;
    default: s = -cr; c = sr; break;
  }
}

}  // namespace pmsim
