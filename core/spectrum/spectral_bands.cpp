#include "core/spectrum/spectral_bands.h"

#include <cmath>

#include "core/spectrum/cie.h"

namespace pmsim {

SpectralBands spectral_bands(int n, Illuminant illuminant, bool weighted) {
  SpectralBands b;
  b.lo_nm.resize(std::size_t(n));
  b.width_nm.resize(std::size_t(n));
  b.weight.assign(std::size_t(n), glm::dvec3(0.0));
  b.moment.assign(std::size_t(n), glm::dvec3(0.0));
  const double span = kVisibleMaxNm - kVisibleMinNm;
  for (int i = 0; i < n; ++i) {
    const std::size_t k = std::size_t(i);
    b.lo_nm[k] = kVisibleMinNm + span * i / n;
    b.width_nm[k] = span / n;
    if (!weighted) continue;
    // Steps that tile the band exactly (a band of 12.5 nm is 13 steps of 0.96 nm: 1 nm steps
    // from its start would cover 12 of its 12.5 nm, and the weights would sum to Y = 0.96).
    const int steps = int(std::ceil(b.width_nm[k] - 1e-9));
    const double dl = b.width_nm[k] / steps;
    for (int s = 0; s < steps; ++s) {
      const double t = (s + 0.5) * dl;
      const glm::dvec3 ws = dl * observer_weight(illuminant, b.lo_nm[k] + t);
      b.weight[k] += ws;
      b.moment[k] += ws * (t - 0.5 * b.width_nm[k]);
    }
  }
  if (weighted) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& w : b.weight) sum += w;
    const glm::dvec3 scale = illuminant_white_xyz(illuminant) / sum;
    for (std::size_t k = 0; k < b.weight.size(); ++k) {
      b.weight[k] *= scale;
      b.moment[k] *= scale;
    }
  }
  for (const glm::dvec3& w : b.weight) b.sum += w;
  return b;
}

}  // namespace pmsim
