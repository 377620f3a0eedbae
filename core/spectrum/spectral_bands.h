#pragma once
// The white-light bands of every renderer (the flat modal renderer's spectral levels, the
// specimen renderers, the lens-ghost image): n equal bands over 380–780 nm, each weighted by
// W_b = ∫_band observer × illuminant dλ, and its first moment M_b = ∫_band observer × illuminant
// (λ − λ_b) dλ about the band's centre λ_b (the linear term of a transmission across the band).
// Quadrature: the midpoint rule at ≤ 1 nm steps that tile the band exactly (the observer tables
// are 1–5 nm data, linear in between). Normalisation: Σ_b W_b is the illuminant's white exactly
// (Y = 1 for T ≡ 1, the exposure) at every n; the sub-rule alone differs from the tables' own
// quadrature by ~10⁻⁶.
#include <vector>

#include <glm/vec3.hpp>

#include "core/spectrum/illuminant.h"

namespace pmsim {

struct SpectralBands {
  std::vector<double> lo_nm, width_nm;
  std::vector<glm::dvec3> weight;  // W_b (XYZ)
  std::vector<glm::dvec3> moment;  // M_b (XYZ · nm)
  glm::dvec3 sum{0.0};             // Σ W_b: the white of T ≡ 1
  int count() const { return int(lo_nm.size()); }
  double centre_nm(int b) const { return lo_nm[std::size_t(b)] + 0.5 * width_nm[std::size_t(b)]; }
};

// `weighted` false: the bands' limits only (monochromatic light, W_b = M_b = 0). n ≥ 1.
SpectralBands spectral_bands(int n, Illuminant illuminant, bool weighted = true);

}  // namespace pmsim
