// Section 8 (Tables 1 and 2): the ray-cone code against paths computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "core/optics/fresnel.h"
#include "core/scene3d/ray_cone.h"

namespace pmsim {
namespace {

TEST(RayCone, OnAxisPathGivesTheNormalIncidenceSeriesWithBeerLambert) {
  // Hand computation. On the axis every node is at normal incidence, so for either polarization
  // T = 1 − R, R = ((n − 1)/(n + 1))² (Born & Wolf 1.5 (21)), and a pass through the glass of
  // thickness t keeps e^(−μt). Out2 = T·e^(−μt)·T, Out4 = T·e^(−μt)·R·e^(−μt)·R·e^(−μt)·T, …:
  //   I2 = T²e^(−μt),  I4 = T²R²e^(−3μt),  I6 = T²R⁴e^(−5μt)  (for I0 = 1),
  // so η4 = q/(1 + q + q²) with q = R²e^(−2μt), η6 = q²/(1 + q + q²).
  // For N-SF11 at 587.56 nm (n = 1.78472): R = (0.78472/2.78472)² = 0.079408, R² = 0.0063056,
  // η4 ≈ 0.0062661 for a lossless lens (the paper's Table 2 lists 0.0060 … 0.0063).
  RayConeSetup s;
  s.sphere_radius_mm = 8.0;
  s.curved_side_to_camera = false;
  s.camera_height_mm = 12.5;
  const Lens lens(ray_cone_lens(s));
  const LensMedia m = lens.media(s.wavelength_nm);
  const double n = m.n_glass, mu = m.attenuation_per_mm, t = lens.geometry().thickness_mm();
  const double R = std::pow((n - 1.0) / (n + 1.0), 2), T = 1.0 - R;
  const RayConePath p = trace_ray_cone_path(lens, s, 0.0);
  EXPECT_TRUE(p.clean);
  // 1e-12: the series is a product of ~10 factors each exact to rounding (1e-16).
  EXPECT_NEAR(p.I2, T * T * std::exp(-mu * t), 1e-12);
  EXPECT_NEAR(p.I4, T * T * R * R * std::exp(-3 * mu * t), 1e-12);
  EXPECT_NEAR(p.I6, T * T * std::pow(R, 4) * std::exp(-5 * mu * t), 1e-14);
  const double q = R * R * std::exp(-2 * mu * t);
  EXPECT_NEAR(p.eta4(), q / (1 + q + q * q), 1e-12);
  EXPECT_NEAR(n, 1.78472, 5e-5);  // SCHOTT catalogue n_d of N-SF11
}

TEST(RayCone, OffAxisParallelRayThroughTheFlatFaceMatchesFresnelAtTheSphere) {
  // Hand computation, right scene at OC = ∞ with Rs = 8: a ray parallel to the axis at height
  // h = 2 mm enters the flat face at normal incidence (T0 = 1 − R) and meets the convex cap
  // from inside at sin α = h/Rs = 0.25 (α = 14.4775°), where it leaves into air with
  // η = 1/n. Out2 = ½·T0·(T_s(α) + T_p(α))·e^(−μL), L the path from the flat face to the cap:
  // L = thickness − sag(h) with sag(h) = Rs − √(Rs² − h²) = 8 − 7.745967 = 0.254033 mm.
  RayConeSetup s;
  s.sphere_radius_mm = 8.0;
  s.curved_side_to_camera = false;
  s.camera_height_mm = std::numeric_limits<double>::infinity();
  const Lens lens(ray_cone_lens(s));
  const LensMedia m = lens.media(s.wavelength_nm);
  const double n = m.n_glass;
  const double R0 = std::pow((n - 1.0) / (n + 1.0), 2);
  const double h = 2.0, Rs = 8.0;
  const double sag = Rs - std::sqrt(Rs * Rs - h * h);
  EXPECT_NEAR(sag, 0.254033, 1e-6);
  const double L = lens.geometry().thickness_mm() - sag;
  const FresnelAmplitudes f = fresnel_amplitudes(std::sqrt(1.0 - std::pow(h / Rs, 2)), 1.0 / n);
  const double expected = 0.5 * (1.0 - R0) * (f.T_s() + f.T_p()) * std::exp(-m.attenuation_per_mm * L);
  const RayConePath p = trace_ray_cone_path(lens, s, h);
  EXPECT_TRUE(p.clean);
  // 1e-12: closed form and SML evaluate the same formulas in a different order.
  EXPECT_NEAR(p.I2, expected, 1e-12);
}

TEST(RayCone, ConeStopsWhereAPathFirstMeetsTheLedge) {
  // The cone ratio is the first radius whose path is not clean; every path inside it is clean
  // and the one just beyond is not (sampling step RL/400).
  RayConeSetup s;
  s.sphere_radius_mm = 4.3;
  s.curved_side_to_camera = false;
  s.camera_height_mm = 8.5;
  const RayConeResult r = ray_cone(s, 401);
  ASSERT_GT(r.eta, 0.05);
  ASSERT_LT(r.eta, 0.999);
  const Lens lens(ray_cone_lens(s));
  EXPECT_TRUE(trace_ray_cone_path(lens, s, r.eta * s.lens_radius_mm).clean);
  EXPECT_FALSE(trace_ray_cone_path(lens, s, (r.eta + 1.0 / 400) * s.lens_radius_mm).clean);
  // Ratios are fractions of the total.
  EXPECT_GT(r.eta4_max, 0.0);
  EXPECT_LT(r.eta4_max, 1.0);
}

}  // namespace
}  // namespace pmsim
