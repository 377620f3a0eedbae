#include "core/specimen/spectral_bands.h"

#include <cmath>

#include "core/spectrum/cie.h"

namespace pmsim {

SpectralBands spectral_bands(int n, Illuminant illuminant, bool weighted) {
  SpectralBands b;
  b.lo_nm.resize(std::size_t(n));
  b.width_nm.resize(std::size_t(n));
  b.weight.assign(std::size_t(n), glm::dvec3(0.0));
  const double span = kVisibleMaxNm - kVisibleMinNm;
  for (int i = 0; i < n; ++i) {
    const std::size_t k = std::size_t(i);
    b.lo_nm[k] = kVisibleMinNm + span * i / n;
    b.width_nm[k] = span / n;
    if (weighted) {
      // The midpoint rule at ≤ 1 nm steps that tile the band exactly (a band of 12.5 nm is 13
      // steps of 0.96 nm: 1 nm steps from its start would cover 12 of its 12.5 nm, and the bands'
      // weights would sum to Y = 0.96).
      const int steps = int(std::ceil(b.width_nm[k] - 1e-9));
      const double dl = b.width_nm[k] / steps;
      for (int s = 0; s < steps; ++s) b.weight[k] += dl * observer_weight(illuminant, b.lo_nm[k] + (s + 0.5) * dl);
    }
    b.sum += b.weight[k];
  }
  return b;
}

}  // namespace pmsim
