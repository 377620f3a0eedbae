#pragma once
// Cauchy's dispersion law (A. L. Cauchy, 1836), the one formula for the media (λ in nm, B in nm²)
// and the minerals (λ in µm, B in µm², C in µm⁴): n(λ) = A + B/λ² + C/λ⁴, B and C in powers of
// the unit of λ. Each caller names its unit (Medium::cauchy(…, B_nm2), IndexDispersion::Cauchy).
namespace pmsim {

constexpr double cauchy_index(double A, double B, double C, double wavelength) {
  const double l2 = wavelength * wavelength;
  return A + B / l2 + C / (l2 * l2);
}

}  // namespace pmsim
