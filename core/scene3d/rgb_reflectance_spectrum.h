#pragma once
// Spectral reflectance from an RGB colour: Smits (1999), "An RGB-to-spectrum conversion for
// reflectances", J. Graphics Tools 4(4):11–22. The smallest channel rides the white basis, the
// rest the complementary (cyan/magenta/yellow) and primary (red/green/blue) bases; the result is
// smooth, bounded by ~1 and reproduces the colour to within a few per cent. Smits tabulates ten
// equal bins over 380–720 nm; beyond 720 nm the last bin is held (reflectances are flat there).
#include <glm/vec3.hpp>

namespace pmsim {

// ρ(λ) for linear RGB in [0,1] (clamped), piecewise constant on Smits' ten bins.
double smits_reflectance(const glm::dvec3& rgb_linear, double wavelength_nm);

}  // namespace pmsim
