// The transformation G at one interface: energy, polarization frame, normal incidence, TIR split.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "core/base/units.h"
#include "core/optics/beer_lambert.h"
#include "core/optics/interaction.h"

using namespace pmsim;

namespace {
PolarizedRay make_ray(glm::dvec3 dir, glm::dvec3 pol, double I = 1.0) {
  PolarizedRay r;
  r.dir = glm::normalize(dir);
  r.pol = glm::normalize(pol - glm::dot(pol, r.dir) * r.dir);
  r.intensity = I;
  return r;
}
bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

TEST(InterfaceEnergy, ReflectedPlusRefractedEqualsIncidentForRandomRays) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> un(1.0, 2.0);
  for (int k = 0; k < 20000; ++k) {
    const PolarizedRay in = make_ray({g(rng), g(rng), g(rng)}, {g(rng), g(rng), g(rng)}, 2.5);
    const glm::dvec3 N = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
    const double n1 = un(rng), n2 = un(rng);
    InteractionResult res;
    interact(in, {0, 0, 0}, N, n1, n2, FresnelModel::Exact, res);
    const double out = res.reflected_intensity() + (res.has_refracted ? res.refracted.intensity : 0);
    // A handful of roundings of O(1) numbers: 1e-14 relative.
    ASSERT_NEAR(out, in.intensity, 1e-14 * in.intensity);
    for (int j = 0; j < res.reflected_count; ++j) {
      const PolarizedRay& r = res.reflected[j];
      // Outgoing v_p is a unit vector ⟂ dir to rounding (1e-14).
      ASSERT_NEAR(glm::length(r.pol), 1.0, 1e-14);
      ASSERT_NEAR(glm::dot(r.pol, r.dir), 0.0, 1e-14);
      // Law of reflection: same angle to the normal.
      ASSERT_NEAR(std::abs(glm::dot(r.dir, N)), std::abs(glm::dot(in.dir, N)), 1e-14);
    }
    if (res.has_refracted) {
      const PolarizedRay& t = res.refracted;
      ASSERT_NEAR(glm::dot(t.pol, t.dir), 0.0, 1e-14);
      // Snell: n1 sinθ1 = n2 sinθ2 (|d × N| is sinθ), 1e-13 for the cross products.
      ASSERT_NEAR(n1 * glm::length(glm::cross(in.dir, N)), n2 * glm::length(glm::cross(t.dir, N)), 1e-13);
    }
  }
}

TEST(InterfaceNormalIncidence, AnyPolarizationReflectsAsMinusPointTwoTimesTheField) {
  // Normal incidence from n=1 onto n=1.5: the reflected field is ((n1−n2)/(n1+n2))·E = −0.2·E and
  // the refracted field 0.8·E as vectors, for every v_p (no basis jump, no NaN).
  for (int k = 0; k < 16; ++k) {
    const double a = k * pmsim::kPi / 8;
    const PolarizedRay in = make_ray({0, 0, 1}, {std::cos(a), std::sin(a), 0});
    InteractionResult res;
    interact(in, {0, 0, 0}, {0, 0, -1}, 1.0, 1.5, FresnelModel::Exact, res);
    ASSERT_EQ(res.reflected_count, 1);
    const PolarizedRay& r = res.reflected[0];
    ASSERT_TRUE(finite(r.pol) && finite(res.refracted.pol));
    // Field = √I·v_p: compare vectors; 1e-15 for rounding of O(1) terms.
    const glm::dvec3 Er = std::sqrt(r.intensity) * r.pol, Ei = in.pol;
    EXPECT_NEAR(glm::length(Er - (-0.2) * Ei), 0.0, 1e-15) << k;
    // Transmitted amplitude: field t = 0.8 with intensity T = 1.5·0.64 = 0.96.
    EXPECT_NEAR(res.refracted.intensity, 0.96, 1e-15);
    EXPECT_NEAR(glm::length(res.refracted.pol - in.pol), 0.0, 1e-15) << k;
    EXPECT_NEAR(glm::length(r.dir - glm::dvec3(0, 0, -1)), 0.0, 1e-15);
  }
}

TEST(InterfaceNormalIncidence, NearNormalIsContinuousWithNormal) {
  // A tilt of 1e-9 rad changes the fields by O(1e-9): 1e-8 fails on any basis jump (which would be O(1)).
  const PolarizedRay in0 = make_ray({0, 0, 1}, {0.6, 0.8, 0});
  const PolarizedRay in1 = make_ray({1e-9, 0, 1}, {0.6, 0.8, 0});
  InteractionResult a, b;
  interact(in0, {0, 0, 0}, {0, 0, 1}, 1.5, 1.0, FresnelModel::Exact, a);
  interact(in1, {0, 0, 0}, {0, 0, 1}, 1.5, 1.0, FresnelModel::Exact, b);
  EXPECT_NEAR(glm::length(a.reflected[0].pol - b.reflected[0].pol), 0.0, 1e-8);
  EXPECT_NEAR(glm::length(a.refracted.pol - b.refracted.pol), 0.0, 1e-8);
}

TEST(InterfaceBrewster, PParallelLightIsNotReflectedAtBrewsterAngle) {
  const double b = brewster_angle_rad(1.5);
  const glm::dvec3 d{std::sin(b), 0, std::cos(b)};
  // Plane of incidence is x–z; p_i lies in it.
  const PolarizedRay in = make_ray(d, {std::cos(b), 0, -std::sin(b)});
  InteractionResult res;
  interact(in, {0, 0, 0}, {0, 0, -1}, 1.0, 1.5, FresnelModel::Exact, res);
  // R_p = r_p² ≈ (1e-16)²: either no reflected ray or one with intensity < 1e-30.
  EXPECT_LT(res.reflected_intensity(), 1e-30);
  EXPECT_NEAR(res.refracted.intensity, 1.0, 1e-15);
}

TEST(InterfaceTir, SplitsIntoPerpendicularAndParallelRaysWithPaperPhases) {
  const double a = 60 * pmsim::kPi / 180, eta = 1.0 / 1.5;
  const glm::dvec3 d{std::sin(a), 0, std::cos(a)};
  // 30% of the intensity in E⊥ (along ±y), 70% in E∥.
  const glm::dvec3 s_dir = glm::normalize(glm::cross(d, glm::dvec3(0, 0, 1)));
  const glm::dvec3 p_dir = glm::cross(d, s_dir);
  PolarizedRay in = make_ray(d, std::sqrt(0.3) * s_dir + std::sqrt(0.7) * p_dir, 2.0);
  in.delta_rad = 0.25;
  InteractionResult res;
  interact(in, {0, 0, 0}, {0, 0, 1}, 1.5, 1.0, FresnelModel::Exact, res);
  ASSERT_TRUE(res.tir);
  ASSERT_FALSE(res.has_refracted);
  ASSERT_EQ(res.reflected_count, 2);
  // Intensities split exactly by the components (rounding only: 1e-15).
  EXPECT_NEAR(res.reflected[0].intensity, 0.6, 1e-15);
  EXPECT_NEAR(res.reflected[1].intensity, 1.4, 1e-15);
  const double q = std::sqrt(std::sin(a) * std::sin(a) - eta * eta);
  EXPECT_NEAR(res.reflected[0].delta_rad, 0.25 + 2 * std::atan(q / std::cos(a)), 1e-14);
  EXPECT_NEAR(res.reflected[1].delta_rad, 0.25 + 2 * std::atan(q / (eta * eta * std::cos(a))) - pmsim::kPi,
              1e-14);
  EXPECT_NEAR(glm::length(glm::cross(res.reflected[0].pol, s_dir)), 0.0, 1e-15);  // E⊥ stays ⟂
  EXPECT_NEAR(glm::dot(res.reflected[1].pol, res.reflected[1].dir), 0.0, 1e-15);
}

TEST(InterfaceGrazing, NoNaNAtCosineOneBillionth) {
  const double c = 1e-9;
  const glm::dvec3 d{std::sqrt(1 - c * c), 0, c};
  const PolarizedRay in = make_ray(d, glm::dvec3(0, 1, 0) + glm::dvec3(-c, 0, 1));
  for (double n2 : {1.5, 1.0 / 1.5}) {
    InteractionResult res;
    interact(in, {0, 0, 0}, {0, 0, -1}, 1.0, n2, FresnelModel::Exact, res);
    ASSERT_GE(res.reflected_count, 1);
    for (int j = 0; j < res.reflected_count; ++j) {
      ASSERT_TRUE(finite(res.reflected[j].pol) && std::isfinite(res.reflected[j].intensity));
    }
    // Nearly everything is reflected: 1 − R = O(cosθ) ≈ 1e-8 or 0.
    EXPECT_NEAR(res.reflected_intensity(), 1.0, 1e-7);
    // Physical field reverses (r → −1 for both components): √R·v_p ≈ −v_p,in (1e-7).
    if (!res.tir) {
      const glm::dvec3 Er = std::sqrt(res.reflected[0].intensity) * res.reflected[0].pol;
      EXPECT_NEAR(glm::length(Er + in.pol), 0.0, 1e-7);
    }
  }
}

TEST(BeerLambert, IntensityDecaysExponentiallyOverKnownPath) {
  // I/I0 = e^(−μx): μ = 0.02/mm over 50 mm gives e^(−1); exp is correctly rounded to 1 ulp.
  EXPECT_NEAR(beer_lambert_transmittance(0.02, 50.0), std::exp(-1.0), 1e-16);
  EXPECT_EQ(beer_lambert_transmittance(0.0, 1e9), 1.0);
  // Two paths in sequence multiply (the law is memoryless): 1e-15 relative.
  EXPECT_NEAR(beer_lambert_transmittance(0.3, 1.0) * beer_lambert_transmittance(0.3, 2.5),
              beer_lambert_transmittance(0.3, 3.5), 1e-15);
  EXPECT_DOUBLE_EQ(optical_path_mm(1.5, 2.0), 3.0);
  // 1 mm of optical path is 1e6/λ[nm] waves.
  EXPECT_NEAR(propagation_phase_rad(0.5e-3, 500.0), 2 * pmsim::kPi, 1e-12);
}

TEST(PolarizationFrame, IsRightHandedForIncidentAndRefractedAndIndependentOfNormalSign) {
  std::mt19937_64 rng(21);
  std::normal_distribution<double> g;
  for (int k = 0; k < 2000; ++k) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
    const glm::dvec3 N = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
    const PolarizationFrame f = polarization_frame(d, N);
    // s ⟂ d and N, s × p_i = d (orthonormal to rounding, 1e-14).
    ASSERT_NEAR(glm::dot(f.s, d), 0.0, 1e-14);
    ASSERT_NEAR(glm::dot(f.s, N), 0.0, 1e-14);
    ASSERT_NEAR(glm::length(glm::cross(f.s, f.p_i) - d), 0.0, 1e-14);
    const glm::dvec3 r = reflect_dir(d, N);
    ASSERT_NEAR(glm::length(glm::cross(p_reflected(f.s, r), f.s) - r), 0.0, 1e-14);
    // The physical outcome does not depend on which way N points (both s and p flip together).
    const PolarizedRay in = make_ray(d, {g(rng), g(rng), g(rng)});
    InteractionResult a, b;
    interact(in, {0, 0, 0}, N, 1.2, 1.7, FresnelModel::Exact, a);
    interact(in, {0, 0, 0}, -N, 1.2, 1.7, FresnelModel::Exact, b);
    ASSERT_EQ(a.reflected_count, b.reflected_count);
    ASSERT_NEAR(glm::length(a.reflected[0].pol - b.reflected[0].pol), 0.0, 1e-14);
    ASSERT_NEAR(glm::length(a.refracted.pol - b.refracted.pol), 0.0, 1e-14);
  }
  // Exactly normal incidence: a valid frame, no NaN.
  const PolarizationFrame f = polarization_frame({0, 0, 1}, {0, 0, -1});
  EXPECT_NEAR(glm::length(f.s), 1.0, 1e-15);
  EXPECT_NEAR(glm::dot(f.s, glm::dvec3(0, 0, 1)), 0.0, 1e-15);
}

TEST(InterfaceOblique, ReflectedFieldAgreesWithBornAndWolfInTheirFrame) {
  // Independent check of the frame convention: Born & Wolf write the reflected field with a
  // right-handed frame (s, p_BW, r), p_BW = r × s = −p_r, and r∥ = tg(α−γ)/tg(α+γ) (no sign flip).
  const double a = 35 * pmsim::kPi / 180, n21 = 1.5;
  const double gam = std::asin(std::sin(a) / n21);
  const glm::dvec3 d{std::sin(a), 0, std::cos(a)}, N{0, 0, -1};
  const PolarizedRay in = make_ray(d, {0.3, 0.8, -0.3 * std::sin(a) / std::cos(a)});
  InteractionResult res;
  interact(in, {0, 0, 0}, N, 1.0, n21, FresnelModel::Exact, res);
  const PolarizationFrame f = polarization_frame(d, N);
  const glm::dvec3 r = res.reflected_dir;
  const glm::dvec3 p_bw = glm::cross(r, f.s);
  const double rs_bw = -std::sin(a - gam) / std::sin(a + gam);
  const double rp_bw = std::tan(a - gam) / std::tan(a + gam);
  const glm::dvec3 E = rs_bw * glm::dot(in.pol, f.s) * f.s + rp_bw * glm::dot(in.pol, f.p_i) * p_bw;
  const glm::dvec3 got = std::sqrt(res.reflected[0].intensity) * res.reflected[0].pol;
  EXPECT_NEAR(glm::length(got - E), 0.0, 1e-14);  // trig rounding of O(1) values
}
