#pragma once
// The white-light bands of the specimen renderers: n equal bands over 380–780 nm, each weighted
// by W_b = ∫_band observer × illuminant dλ (Y of all bands = 1 for T ≡ 1, the exposure).
#include <vector>

#include <glm/vec3.hpp>

#include "core/spectrum/illuminant.h"

namespace pmsim {

struct SpectralBands {
  std::vector<double> lo_nm, width_nm;
  std::vector<glm::dvec3> weight;  // W_b (XYZ)
  glm::dvec3 sum{0.0};             // Σ W_b: the white of T ≡ 1
  int count() const { return int(lo_nm.size()); }
};

// `weighted` false: the bands' limits only (monochromatic light, W_b = 0).
SpectralBands spectral_bands(int n, Illuminant illuminant, bool weighted = true);

}  // namespace pmsim
