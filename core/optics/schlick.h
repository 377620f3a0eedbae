#pragma once
// APPROXIMATE reflectance: Schlick (1994), "An inexpensive BRDF model for physically-based
// rendering", Comput. Graph. Forum 13(3) eq. 24:  R(θ) ≈ R0 + (1 − R0)(1 − cosθ)^5,
// R0 = ((n1 − n2)/(n1 + n2))². It knows nothing of polarization and is used only where the user
// asks for it (FresnelModel::Schlick), e.g. to reproduce the paper's Fig. 4 comparison. Going from
// the denser medium, θ is the angle on the denser side (θt), so TIR still gives R = 1.
#include <cmath>

#include "core/optics/fresnel.h"

namespace pmsim {

// cos_i, eta as in fresnel_amplitudes (eta = n_t/n_i, negative cos_i swaps sides).
inline double schlick_reflectance(double cos_i, double eta) {
  if (cos_i < 0.0) {
    cos_i = -cos_i;
    eta = 1.0 / eta;
  }
  const double r0 = (1.0 - eta) / (1.0 + eta);
  const double R0 = r0 * r0;
  double c = std::min(cos_i, 1.0);
  if (eta < 1.0) {
    const double cos_t2 = snell_cos_t2(c, eta);
    if (cos_t2 < 0.0) return 1.0;
    c = std::sqrt(cos_t2);
  }
  const double m = 1.0 - c;
  const double m2 = m * m;
  return R0 + (1.0 - R0) * m2 * m2 * m;
}

// APPROXIMATE amplitudes built from schlick_reflectance: both components get |r| = √R with the
// sign of the normal-incidence ratio (n1 − n2)/(n1 + n2), and t chosen so that each component
// keeps R + T = 1. TIR is left to the exact formulas (Schlick has no phase).
inline FresnelAmplitudes schlick_amplitudes(double cos_i, double eta) {
  FresnelAmplitudes f = fresnel_amplitudes(cos_i, eta);
  if (f.tir) return f;
  const double R = schlick_reflectance(f.cos_i, f.eta);
  const double r = std::sqrt(R) * (f.eta > 1.0 ? -1.0 : 1.0);
  f.r_s = r;
  f.r_p = r;
  const double pf = f.power_factor();
  const double t = pf > 0.0 ? std::sqrt(std::max(0.0, 1.0 - R) / pf) : 0.0;
  f.t_s = t;
  f.t_p = t;
  return f;
}

}  // namespace pmsim
