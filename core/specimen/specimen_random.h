#pragma once
// The one random number source of the specimen module: SplitMix64 (core/base/splitmix64.h),
// stateless per call so that a pixel's samples depend on (pixel, sample) only, not on the thread
// that draws them.
#include <cmath>
#include <cstdint>

#include "core/base/splitmix64.h"

namespace pmsim {

struct SpecimenRandom {
  std::uint64_t state;
  explicit SpecimenRandom(std::uint64_t seed) : state(splitmix64(seed)) {}
  // Uniform in [0, 1): the top 53 bits.
  double uniform() {
    state = splitmix64(state);
    return unit_interval(state);
  }
};

// The R-sequence step in 5 dimensions (point jx, jy, pupil or cone u1, u2, wavelength jitter):
// α_j = φ⁻ʲ with φ the real root of x⁶ = x + 1 (M. Roberts, "The unreasonable effectiveness of
// quasirandom sequences", 2018). Shifted by a random point (Cranley–Patterson rotation) it stays
// unbiased and is stratified over k.
constexpr double kPhi5 = 1.1673039782614187;
struct SampleDims {
  double v[5];
};
inline SampleDims kronecker(const SampleDims& shift, int k) {
  SampleDims s;
  double a = 1.0;
  for (int j = 0; j < 5; ++j) {
    a /= kPhi5;
    const double x = shift.v[j] + a * k;
    s.v[j] = x - std::floor(x);
  }
  return s;
}

}  // namespace pmsim
