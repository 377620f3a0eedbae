#pragma once
// Fresnel amplitude ratios at a plane interface between two isotropic, non-absorbing media.
//
// Conventions (docs/conventions.md; polarization_frame.h for the vectors):
//  * eta = n_t / n_i (the paper's n21 = n2/n1). cos_i ≥ 0 is measured from the normal on the
//    incident side; a negative cos_i means the ray arrives from the other side, so the sides swap
//    (eta → 1/eta, cos_i → −cos_i), as in pbrt's FrDielectric.
//  * Amplitudes are ratios of field components in the frame s = unit(d × N), p_i = d × s,
//    p_t = t × s, p_r = s × r. The incident and refracted frames are right-handed (s × p = dir),
//    the reflected one left-handed, so r_p here is −(Born & Wolf's r∥). In this frame the paper's
//    phase-jump rules describe the signs of r_s and r_p, its normal-incidence ratio
//    (n1 − n2)/(n1 + n2) is the common limit of r_s and r_p, and its TIR phases δ⊥, δ∥ (with the
//    −π) are exactly −arg r_s, −arg r_p for a field written √I·v_p·e^(−iδ).
//  * The paper writes the ratios with angles (sin(α−γ)/sin(α+γ), tg(α−γ)/tg(α+γ), …); we use the
//    equivalent cosine forms, which have no 0/0 at normal incidence and no cancellation at grazing
//    incidence (Born & Wolf §1.5.2 (21a), (21b)).
#include <algorithm>
#include <cmath>
#include <complex>

#include "core/base/units.h"

namespace pmsim {

struct FresnelAmplitudes {
  std::complex<double> r_s, r_p;  // reflected / incident field component (TIR: |r| = 1)
  double t_s = 0.0, t_p = 0.0;    // refracted / incident field component (0 under TIR)
  double cos_i = 1.0;             // cosθi after the side swap (≥ 0)
  double cos_t = 1.0;             // cosθt ≥ 0 (0 under TIR)
  double eta = 1.0;               // n_t / n_i after the side swap
  bool tir = false;
  // Power coefficients. T carries the beam-cross-section and impedance factor
  // n_t·cosθt / (n_i·cosθi), so that R + T = 1 (Born & Wolf §1.5.3 (39)–(41)).
  double R_s() const { return std::norm(r_s); }
  double R_p() const { return std::norm(r_p); }
  double power_factor() const { return cos_i > 0.0 ? eta * cos_t / cos_i : 0.0; }
  double T_s() const { return power_factor() * t_s * t_s; }
  double T_p() const { return power_factor() * t_p * t_p; }
};

// cos²θt from Snell's law n_i sinθi = n_t sinθt: cos²θt = 1 − sin²θi/η² = (cos²θi + η² − 1)/η².
// Negative means TIR. The second form, with η² − 1 = (η−1)(η+1), avoids the cancellation of
// 1 − sin²θi/η² at grazing incidence when η ≈ 1 (relative error 1e-16 instead of 1e-5).
inline double snell_cos_t2(double cos_i, double eta) {
  return (cos_i * cos_i + (eta - 1.0) * (eta + 1.0)) / (eta * eta);
}

// TIR phase jumps of the paper (§6, after Sivukhin): field reflected = field·e^(−iδ).
// δ⊥ = 2·atan(√(sin²α − n21²)/cosα);  δ∥ = 2·atan(√(sin²α − n21²)/(n21²·cosα)) − π.
// atan2 keeps both finite at grazing incidence (cosα → 0).
inline double tir_delta_s(double cos_i, double eta) {
  const double sin2_i = std::max(0.0, (1.0 - cos_i) * (1.0 + cos_i));
  const double q = std::sqrt(std::max(0.0, sin2_i - eta * eta));
  return 2.0 * std::atan2(q, cos_i);
}
inline double tir_delta_p(double cos_i, double eta) {
  const double sin2_i = std::max(0.0, (1.0 - cos_i) * (1.0 + cos_i));
  const double q = std::sqrt(std::max(0.0, sin2_i - eta * eta));
  return 2.0 * std::atan2(q, eta * eta * cos_i) - kPi;
}

inline FresnelAmplitudes fresnel_amplitudes(double cos_i, double eta) {
  FresnelAmplitudes f;
  if (cos_i < 0.0) {
    cos_i = -cos_i;
    eta = 1.0 / eta;
  }
  cos_i = std::min(cos_i, 1.0);
  f.cos_i = cos_i;
  f.eta = eta;
  const double cos_t2 = snell_cos_t2(cos_i, eta);
  if (cos_t2 < 0.0) {
    // Total internal reflection: |r| = 1 (the paper's E_r = E), phases from tir_delta_*.
    f.tir = true;
    f.cos_t = 0.0;
    f.r_s = std::polar(1.0, -tir_delta_s(cos_i, eta));
    f.r_p = std::polar(1.0, -tir_delta_p(cos_i, eta));
    return f;
  }
  const double cos_t = std::sqrt(cos_t2);
  f.cos_t = cos_t;
  // r⊥ = −sin(α−γ)/sin(α+γ) = (cosθi − η cosθt)/(cosθi + η cosθt)       (Born & Wolf 1.5 (21b))
  // t⊥ = 2 cosα sinγ/sin(α+γ) = 2 cosθi/(cosθi + η cosθt)                (Born & Wolf 1.5 (21a))
  // r∥ in our reflected frame = −tg(α−γ)/tg(α+γ) = (cosθt − η cosθi)/(cosθt + η cosθi)
  // t∥ = 2 cosα sinγ/(sin(α+γ)cos(α−γ)) = 2 cosθi/(cosθt + η cosθi)      (Born & Wolf 1.5 (21a))
  // At cosθi = 1: r = (1 − η)/(1 + η) = (n1 − n2)/(n1 + n2), t = 2/(1 + η) = 2n1/(n1 + n2).
  const double ds = cos_i + eta * cos_t;
  const double dp = cos_t + eta * cos_i;
  // ds, dp > 0 unless both cosines vanish (grazing exactly at the critical angle, η = 1 only).
  f.r_s = ds > 0.0 ? (cos_i - eta * cos_t) / ds : -1.0;
  f.r_p = dp > 0.0 ? (cos_t - eta * cos_i) / dp : 1.0;
  f.t_s = ds > 0.0 ? 2.0 * cos_i / ds : 0.0;
  f.t_p = dp > 0.0 ? 2.0 * cos_i / dp : 0.0;
  return f;
}

// Power reflectance averaged over s and p: natural (unpolarized) light, the paper's I/2 + I/2.
inline double fresnel_reflectance_unpolarized(double cos_i, double eta) {
  const FresnelAmplitudes f = fresnel_amplitudes(cos_i, eta);
  return 0.5 * (f.R_s() + f.R_p());
}

// Brewster angle tg β = n2/n1 (paper §6), and the critical angle sin θc = n2/n1 (n2 < n1).
inline double brewster_angle_rad(double eta) { return std::atan(eta); }
inline double critical_angle_rad(double eta) { return eta < 1.0 ? std::asin(eta) : kPi / 2; }

}  // namespace pmsim
