#include "core/spectrum/cie.h"

#include <array>

#include "core/spectrum/cie_tables.h"
#include "core/spectrum/table_lookup.h"

namespace pmsim {

glm::dvec3 cie1931_xyz_bar(double wavelength_nm) {
  int i = 0;
  double f = 0.0;
  detail::visible_table_position(wavelength_nm, "cie1931_xyz_bar", i, f);
  auto lerp = [&](const double* t) { return t[i] + f * (t[i + 1] - t[i]); };
  return {lerp(cie_tables::kXBar), lerp(cie_tables::kYBar), lerp(cie_tables::kZBar)};
}

namespace {

// Per illuminant: K = ∫S·ȳ dλ and the white XYZ/K, both by the trapezoid rule on a 1 nm grid over
// the linearly interpolated tables. Using the same rule for K and for the white makes Y_white = 1
// to rounding; ∫ observer_weight_y dλ = 1 holds for that rule.
struct IlluminantNorm {
  double k = 1.0;
  glm::dvec3 white{0.0};
};

IlluminantNorm compute_norm(Illuminant illum) {
  glm::dvec3 sum(0.0);
  for (int nm = 380; nm <= 780; ++nm) {
    const double w = (nm == 380 || nm == 780) ? 0.5 : 1.0;  // trapezoid, h = 1 nm
    sum += w * illuminant_spd(illum, nm) * cie1931_xyz_bar(nm);
  }
  IlluminantNorm n;
  n.k = sum.y;
  n.white = sum / sum.y;
  return n;
}

const IlluminantNorm& norm(Illuminant illum) {
  static const std::array<IlluminantNorm, 2> norms = {compute_norm(Illuminant::D65),
                                                      compute_norm(Illuminant::A)};
  return norms[illum == Illuminant::A ? 1 : 0];
}

}  // namespace

glm::dvec3 observer_weight(Illuminant illum, double wavelength_nm) {
  return illuminant_spd(illum, wavelength_nm) * cie1931_xyz_bar(wavelength_nm) / norm(illum).k;
}

glm::dvec3 illuminant_white_xyz(Illuminant illum) { return norm(illum).white; }

}  // namespace pmsim
