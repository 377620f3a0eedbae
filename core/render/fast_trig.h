#pragma once
// sin and cos together for the spectral inner loop, where libm's calls dominated the profile.
// Range reduction by k = round(x·2/π) with π/2 split in two parts (Cody–Waite), then the Taylor
// polynomials on |r| ≤ π/4 to degree 13/14 (truncation < 4e-13). Phases up to ~1e7 rad keep
// ≲1e-9 absolute error: enough for interference phases of 10 mm plates.
#include <cmath>
#include <cstdint>

namespace pmsim {

// The Cody–Waite split of π/2 and the reduction factor, shared by fast_sincos and the 2- and 4-lane
// version in spectral_level.cpp.
constexpr double kTwoOverPi = 0.63661977236758134308;
constexpr double kPio2Hi = 1.5707963267341256;     // first 33 bits of π/2
constexpr double kPio2Lo = 6.077100506506192e-11;  // π/2 − kPio2Hi

// Taylor polynomials of sin and cos on the reduced argument |r| ≤ π/4 (truncation < 4e-13), for a
// double or a vector of doubles (GCC/Clang vector extensions).
// always_inline: the renderer's AVX2 kernel inlines it to compile it for that target.
template <class T>
[[gnu::always_inline]] inline void sincos_taylor(T r, T& sr, T& cr) {
  const T r2 = r * r;
  sr = r * (1.0 + r2 * (-1.0 / 6 +
                        r2 * (1.0 / 120 +
                              r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 + r2 * (-1.0 / 39916800 +
                                                                             r2 * (1.0 / 6227020800.0)))))));
  cr = 1.0 +
       r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 +
                                           r2 * (1.0 / 40320 + r2 * (-1.0 / 3628800 +
                                                                     r2 * (1.0 / 479001600.0 +
                                                                           r2 * (-1.0 / 87178291200.0)))))));
}

inline void fast_sincos(double x, double& s, double& c) {
  const double k = std::nearbyint(x * kTwoOverPi);
  const double r = (x - k * kPio2Hi) - k * kPio2Lo;
  double sr, cr;
  sincos_taylor(r, sr, cr);
  const std::int64_t q = static_cast<std::int64_t>(k) & 3;
  switch (q) {
    case 0:
      s = sr;
      c = cr;
      break;
    case 1:
      s = cr;
      c = -sr;
      break;
    case 2:
      s = -sr;
      c = -cr;
      break;
    default:
      s = -cr;
      c = sr;
      break;
  }
}

}  // namespace pmsim
