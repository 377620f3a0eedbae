// Closed-form checks of the Fresnel amplitudes, the polarization frame convention and TIR phases.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/base/units.h"
#include "core/optics/fresnel.h"
#include "core/optics/schlick.h"

using namespace pmsim;

namespace {
double cos_from_deg(double deg) { return std::cos(deg * pmsim::kPi / 180.0); }
}  // namespace

TEST(FresnelNormalIncidence, ReflectanceIsFourPercentForGlassOfIndexOnePointFive) {
  const FresnelAmplitudes f = fresnel_amplitudes(1.0, 1.5);
  // ((1 − 1.5)/(1 + 1.5))² = 0.04 exactly in real arithmetic; 1e-15 allows a few roundings.
  EXPECT_NEAR(f.R_s(), 0.04, 1e-15);
  EXPECT_NEAR(f.R_p(), 0.04, 1e-15);
  // The paper's ratios (n1 − n2)/(n1 + n2) = −0.2 and 2n1/(n1 + n2) = 0.8, same for s and p in
  // our frame (no basis jump at normal incidence).
  EXPECT_NEAR(f.r_s.real(), -0.2, 1e-15);
  EXPECT_NEAR(f.r_p.real(), -0.2, 1e-15);
  EXPECT_NEAR(f.t_s, 0.8, 1e-15);
  EXPECT_NEAR(f.t_p, 0.8, 1e-15);
  EXPECT_NEAR(f.T_s(), 0.96, 1e-15);
}

TEST(FresnelNormalIncidence, LimitIsContinuousFromObliqueIncidence) {
  // r(θ) − r(0) = O(θ²); at θ = 1e-6 rad the difference is ~1e-12, so 1e-11 fails on any jump.
  const FresnelAmplitudes f0 = fresnel_amplitudes(1.0, 1.5);
  const FresnelAmplitudes f1 = fresnel_amplitudes(std::cos(1e-6), 1.5);
  EXPECT_NEAR(f1.r_s.real(), f0.r_s.real(), 1e-11);
  EXPECT_NEAR(f1.r_p.real(), f0.r_p.real(), 1e-11);
  EXPECT_NEAR(f1.t_s, f0.t_s, 1e-11);
  EXPECT_NEAR(f1.t_p, f0.t_p, 1e-11);
}

TEST(FresnelOblique, AmplitudeRatiosAt45DegreesFromAirToGlass) {
  const FresnelAmplitudes f = fresnel_amplitudes(cos_from_deg(45.0), 1.5);
  // Reference values to 8 digits (issue #2): tolerance is half a unit of the last digit.
  EXPECT_NEAR(std::abs(f.r_s), 0.30333705, 5e-9);
  EXPECT_NEAR(std::abs(f.r_p), 0.09201336, 5e-9);
  // Below Brewster going into the denser medium both components flip (paper's rules): r < 0.
  EXPECT_LT(f.r_s.real(), 0.0);
  EXPECT_LT(f.r_p.real(), 0.0);
}

TEST(FresnelOblique, PaperAngleFormulasAgreeWithCosineForms) {
  // The paper's four formulas in angles, evaluated directly at α = 50°, n21 = 1.7; agreement to
  // 1e-14 (both are O(1) expressions of well-conditioned trig values).
  const double a = 50.0 * pmsim::kPi / 180.0, n21 = 1.7;
  const double g = std::asin(std::sin(a) / n21);
  const FresnelAmplitudes f = fresnel_amplitudes(std::cos(a), n21);
  EXPECT_NEAR(f.r_s.real(), -std::sin(a - g) / std::sin(a + g), 1e-14);
  EXPECT_NEAR(f.t_s, 2 * std::cos(a) * std::sin(g) / std::sin(a + g), 1e-14);
  // r∥ of the paper, sign by its flip rule (our frame): −tg(α−γ)/tg(α+γ).
  EXPECT_NEAR(f.r_p.real(), -std::tan(a - g) / std::tan(a + g), 1e-14);
  EXPECT_NEAR(f.t_p, 2 * std::cos(a) * std::sin(g) / (std::sin(a + g) * std::cos(a - g)), 1e-14);
}

TEST(FresnelBrewster, ParallelReflectionVanishesAndChangesSignAcrossBrewsterAngle) {
  for (double eta : {1.5, 1.0 / 1.5}) {
    const double b = brewster_angle_rad(eta);
    const FresnelAmplitudes at = fresnel_amplitudes(std::cos(b), eta);
    // r_p is a difference of O(1) terms: zero to a few ulps.
    EXPECT_NEAR(at.r_p.real(), 0.0, 1e-15) << eta;
    const double below = fresnel_amplitudes(std::cos(b - 0.01), eta).r_p.real();
    const double above = fresnel_amplitudes(std::cos(b + 0.01), eta).r_p.real();
    // Paper's rule: E∥ flips (r_p < 0) for n1<n2 below β and for n1>n2 above β.
    if (eta > 1) {
      EXPECT_LT(below, 0.0);
      EXPECT_GT(above, 0.0);
    } else {
      EXPECT_GT(below, 0.0);
      EXPECT_LT(above, 0.0);
    }
  }
}

TEST(FresnelTir, StartsExactlyAtTheCriticalAngle) {
  const double eta = 1.0 / 1.5;
  const double c = critical_angle_rad(eta);
  EXPECT_NEAR(std::sin(c), eta, 1e-15);  // sinθc = n2/n1 to rounding
  EXPECT_FALSE(fresnel_amplitudes(std::cos(c - 1e-7), eta).tir);
  EXPECT_TRUE(fresnel_amplitudes(std::cos(c + 1e-7), eta).tir);
  // Approaching θc from below, transmission goes to 0 continuously: T_p ≈ 4cosθt/(η cosθi) with
  // cosθt ≈ √(2Δθ·tanθc) ≈ 4e-5 at Δθ = 1e-9, i.e. T ≈ 3.4e-4 < 1e-3 (T_s is smaller still).
  const FresnelAmplitudes f = fresnel_amplitudes(std::cos(c - 1e-9), eta);
  EXPECT_LT(f.T_s(), 1e-3);
  EXPECT_LT(f.T_p(), 1e-3);
  EXPECT_GT(f.T_p(), 1e-5);  // but not yet zero: no premature TIR
}

TEST(FresnelTir, ReflectionIsTotalWithThePapersPhases) {
  const double eta = 1.0 / 1.5;
  for (double deg : {42.0, 50.0, 60.0, 75.0, 89.0}) {
    const double a = deg * pmsim::kPi / 180.0;
    const FresnelAmplitudes f = fresnel_amplitudes(std::cos(a), eta);
    ASSERT_TRUE(f.tir) << deg;
    EXPECT_NEAR(std::abs(f.r_s), 1.0, 1e-15);  // |r| = 1: a unit-modulus polar value
    EXPECT_NEAR(std::abs(f.r_p), 1.0, 1e-15);
    EXPECT_EQ(f.T_s(), 0.0);
    const double q = std::sqrt(std::sin(a) * std::sin(a) - eta * eta);
    const double d_perp = 2 * std::atan(q / std::cos(a));                            // paper δ⊥
    const double d_par = 2 * std::atan(q / (eta * eta * std::cos(a))) - pmsim::kPi;  // paper δ∥
    // r = e^(−iδ); compare the complex numbers (phase wrap-free), 1e-14 for trig rounding.
    EXPECT_NEAR(std::abs(f.r_s - std::polar(1.0, -d_perp)), 0.0, 1e-14) << deg;
    EXPECT_NEAR(std::abs(f.r_p - std::polar(1.0, -d_par)), 0.0, 1e-14) << deg;
  }
}

TEST(FresnelTir, MaximumRetardanceMatchesClosedForm) {
  // Retardance Δ = δ∥ + π − δ⊥ (Hecht §8.6 / Azzam 2004 tan(Δ/2) = cosθ√(sin²θ−η²)/sin²θ),
  // maximal at cos²θ = (1 − η²)/(1 + η²) where Δmax = 2·atan((1 − η²)/(2η)).
  for (double n : {1.5, 1.7847, 2.4}) {
    const double eta = 1.0 / n;
    auto retard = [&](double c) { return tir_delta_p(c, eta) + pmsim::kPi - tir_delta_s(c, eta); };
    const double c_max = std::sqrt((1 - eta * eta) / (1 + eta * eta));
    const double expect = 2 * std::atan((1 - eta * eta) / (2 * eta));
    EXPECT_NEAR(retard(c_max), expect, 1e-13) << n;  // trig rounding of O(1) angles
    // It is a maximum: 1e-3 away in cosθ the retardance is lower (quadratic drop ~1e-7 > 0).
    EXPECT_LT(retard(c_max + 1e-3), retard(c_max));
    EXPECT_LT(retard(c_max - 1e-3), retard(c_max));
  }
}

TEST(FresnelGrazing, ReflectedFieldIsMinusIncidentWithoutNaN) {
  for (double eta : {1.5, 1.0 / 1.5, 1.0001}) {
    const FresnelAmplitudes f = fresnel_amplitudes(1e-9, eta);
    ASSERT_TRUE(std::isfinite(f.r_s.real()) && std::isfinite(f.r_s.imag()));
    ASSERT_TRUE(std::isfinite(f.r_p.real()) && std::isfinite(f.r_p.imag()));
    ASSERT_TRUE(std::isfinite(f.t_s) && std::isfinite(f.t_p));
    // r_s → −1; in our reflected frame p_r → −p_i at grazing, so the physical r∥ → −1 appears as
    // r_p → +1. Deviation is O(cosθ/√(η²−1)) ≈ 1e-8 (or exactly 0 under TIR): 1e-6.
    EXPECT_NEAR(std::abs(f.r_s - std::complex<double>(-1.0)), 0.0, 1e-6) << eta;
    EXPECT_NEAR(std::abs(f.r_p - std::complex<double>(1.0)), 0.0, 1e-6) << eta;
  }
  const FresnelAmplitudes z = fresnel_amplitudes(0.0, 1.5);
  EXPECT_EQ(z.r_s.real(), -1.0);
  EXPECT_EQ(z.r_p.real(), 1.0);
  EXPECT_EQ(z.T_s(), 0.0);
}

TEST(FresnelEnergy, ReflectancePlusTransmittanceIsOne) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uc(0.0, 1.0), un(0.3, 3.0);
  for (int k = 0; k < 10000; ++k) {
    const double c = uc(rng), eta = un(rng);
    const FresnelAmplitudes f = fresnel_amplitudes(c, eta);
    // Each is a sum of a few rounded O(1) terms: 4e-15 leaves margin over ~10 ulp.
    EXPECT_NEAR(f.R_s() + f.T_s(), 1.0, 4e-15);
    EXPECT_NEAR(f.R_p() + f.T_p(), 1.0, 4e-15);
  }
}

TEST(FresnelReciprocity, TransmittanceIsTheSameBothWays) {
  // Stokes relations: T(n1→n2, θ1) = T(n2→n1, θ2). 1e-14 for rounding.
  const double eta = 1.5, c1 = cos_from_deg(33.0);
  const FresnelAmplitudes a = fresnel_amplitudes(c1, eta);
  const FresnelAmplitudes b = fresnel_amplitudes(a.cos_t, 1.0 / eta);
  EXPECT_NEAR(a.T_s(), b.T_s(), 1e-14);
  EXPECT_NEAR(a.T_p(), b.T_p(), 1e-14);
  // Negative cos_i swaps sides: same as calling with 1/eta.
  const FresnelAmplitudes c = fresnel_amplitudes(-a.cos_t, eta);
  EXPECT_EQ(c.T_s(), b.T_s());
}

TEST(SchlickApproximation, ExactAtNormalIncidenceAndCloseNearIt) {
  EXPECT_NEAR(schlick_reflectance(1.0, 1.5), 0.04, 1e-15);  // R0 exactly
  // For n = 1.5 Schlick's curve is known to stay within ~0.036 of the unpolarized Fresnel
  // reflectance (worst near 80°). Bound it by 0.04, and check it is really an approximation
  // (worst error above 0.02), so neither curve can silently turn into the other.
  double worst = 0.0;
  for (double deg = 0; deg < 90; deg += 0.5) {
    worst = std::max(worst, std::abs(schlick_reflectance(cos_from_deg(deg), 1.5) -
                                     fresnel_reflectance_unpolarized(cos_from_deg(deg), 1.5)));
  }
  EXPECT_LT(worst, 0.04);
  EXPECT_GT(worst, 0.02);
  EXPECT_EQ(schlick_reflectance(cos_from_deg(60), 1.0 / 1.5), 1.0);  // TIR
  const FresnelAmplitudes s = schlick_amplitudes(cos_from_deg(30), 1.5);
  EXPECT_NEAR(s.R_s() + s.T_s(), 1.0, 1e-15);  // constructed to conserve energy
}
