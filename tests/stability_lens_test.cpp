// Numerical stability of the SML (core/lens): degenerate lenses (plane–plane, hemisphere, cap
// radius equal to the aperture), TIR cascades at large dT with split TIR (ray count and memory
// bounded), and optical paths of 200 mm — where float would lose the interference phase and
// double (or carried differences) keeps it.
#include <cmath>
#include <random>
#include <type_traits>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/base/units.h"
#include "core/lens/lens.h"
#include "core/lens/lens_tracer.h"

namespace pmsim {
namespace {

LensMedia bk7_like() { return {1.5168, 1.0, 0.0}; }

LensSpec spec(double aperture, double front, double back, double ledge) {
  LensSpec s;
  s.radius_mm = aperture;
  s.front_radius_mm = front;
  s.back_radius_mm = back;
  s.ledge_mm = ledge;
  return s;
}

PolarizedRay ray(const glm::dvec3& o, const glm::dvec3& d, double pol_angle) {
  PolarizedRay r;
  r.origin = o;
  r.dir = glm::normalize(d);
  glm::dvec3 a = glm::cross(r.dir, glm::dvec3(0.37, 0.61, 0.7));
  a = glm::normalize(a);
  const glm::dvec3 b = glm::cross(r.dir, a);
  r.pol = std::cos(pol_angle) * a + std::sin(pol_angle) * b;
  r.intensity = 1.0;
  return r;
}

// Every outgoing ray finite, unit, polarization ⟂ direction; energy balanced.
void check_bundle(const LensBundle& b, const std::string& what) {
  for (const PolarizedRay& r : b.rays) {
    ASSERT_TRUE(std::isfinite(r.intensity) && r.intensity >= 0.0) << what;
    ASSERT_TRUE(std::isfinite(r.origin.x + r.origin.y + r.origin.z)) << what;
    ASSERT_TRUE(std::isfinite(r.optical_path_mm) && std::isfinite(r.delta_rad)) << what;
    EXPECT_NEAR(glm::length(r.dir), 1.0, 1e-12) << what;
    EXPECT_NEAR(glm::length(r.pol), 1.0, 1e-9) << what;
    EXPECT_LT(std::fabs(glm::dot(r.pol, r.dir)), 1e-9) << what;
  }
  for (const LensEvent& e : b.events) ASSERT_TRUE(std::isfinite(e.intensity) && e.intensity >= 0.0) << what;
  // Bookkeeping closes to ~1e-16 per interaction (lens_tracer.h); a few hundred interactions at
  // most here: 1e-12 relative.
  EXPECT_LT(std::fabs(b.energy_defect()), 1e-12 * std::max(1.0, b.incident)) << what;
}

TEST(StabilityLens, DegenerateLensesTraceFiniteBalancedBundles) {
  struct Case {
    const char* name;
    LensSpec s;
  };
  const Case cases[] = {
      {"plane-plane slab",
       [] {
         auto s = spec(5.0, 0.0, 0.0, 2.0);
         return s;
       }()},
      {"hemisphere (R = aperture, plane back)", spec(5.0, 5.0, 0.0, 0.0)},
      {"ball (both R = aperture, no ledge)", spec(5.0, 5.0, -5.0, 0.0)},
      {"meniscus-like R = aperture both same sign", spec(5.0, 5.0, 5.0, 1.0)},
      {"paper lens R_L 4.25 R_s 4.3", spec(4.25, 4.3, -4.3, 0.3)},
  };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Case& c : cases) {
    const LensGeometry g(c.s);
    const double rho = g.aperture_radius_mm();
    const glm::dvec3 fv = g.front_vertex();
    std::vector<PolarizedRay> rays = {
        ray(fv - glm::dvec3(0, 0, 10), {0, 0, 1}, 0.0),                   // on the axis, normal incidence
        ray(fv + glm::dvec3(rho, 0, -10), {0, 0, 1}, 0.5),                // exactly at the rim
        ray(fv + glm::dvec3(rho * (1 - 1e-12), 0, -10), {0, 0, 1}, 1.0),  // 1e-12 inside the rim
        ray(g.center() + glm::dvec3(-20, 0, 0), {1, 0, 1e-9}, 0.2),       // grazing through the middle
        ray(g.center() + glm::dvec3(0, -20, 0.1), {0, 1, 0}, 0.3),        // ⟂ axis
        ray(g.center(), {0, 0, 1}, 0.0),                                  // starting inside
    };
    for (int i = 0; i < 200; ++i)
      rays.push_back(ray(g.center() + glm::dvec3(u(rng), u(rng), u(rng)) * (3.0 * g.size_mm()),
                         {u(rng), u(rng), u(rng) + 1e-3}, 3.0 * u(rng)));
    for (int dT : {0, 1, 3, 5})
      for (TirMode tir : {TirMode::Stop, TirMode::Split}) {
        LensTraceOptions opt;
        opt.max_depth = dT;
        opt.tir = tir;
        for (std::size_t i = 0; i < rays.size(); ++i) {
          LensBundle b;
          trace_lens(g, bk7_like(), rays[i], opt, b);
          check_bundle(b, std::string(c.name) + " ray " + std::to_string(i) + " dT " + std::to_string(dT));
          if (::testing::Test::HasFatalFailure()) return;
        }
      }
  }
}

TEST(StabilityLens, AxialRayThroughAPlanePlaneSlabLosesExactlyTheTwoFresnelReflections) {
  // Normal incidence on a slab, dT = 0: T = (1 − R)², R = ((n − 1)/(n + 1))² (Born & Wolf §1.5.3);
  // closed form, rounding only: 1e-14.
  const LensGeometry g(spec(5.0, 0.0, 0.0, 2.0));
  LensTraceOptions opt;
  opt.max_depth = 0;
  LensBundle b;
  trace_lens(g, bk7_like(), ray(g.front_vertex() - glm::dvec3(0, 0, 1), {0, 0, 1}, 0.0), opt, b);
  const double n = bk7_like().n_glass, R = std::pow((n - 1) / (n + 1), 2);
  double forward = 0.0;
  for (const PolarizedRay& r : b.rays)
    if (r.dir.z > 0) forward += r.intensity;
  EXPECT_NEAR(forward, (1 - R) * (1 - R), 1e-14);
}

TEST(StabilityLens, SplitTirCascadesAtLargeDepthStayBoundedInRaysAndEnergy) {
  // A hemisphere entered near its rim sends light onto the plane face beyond the critical angle;
  // with split TIR every total reflection doubles the rays. The tracer must stop at
  // max_internal_rays (reporting the rest as DepthLimit events) and keep the energy balance.
  const LensGeometry g(spec(5.0, 5.0, 0.0, 0.0));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int dT : {10, 40}) {
    LensTraceOptions opt;
    opt.max_depth = dT;
    opt.tir = TirMode::Split;
    opt.max_internal_rays = 4096;
    std::size_t worst = 0;
    int limited = 0;
    for (int i = 0; i < 200; ++i) {
      const double r = 5.0 * (0.7 + 0.3 * u(rng)), a = 2 * kPi * u(rng);
      const glm::dvec3 target =
          g.front_vertex() + glm::dvec3(r * std::cos(a), r * std::sin(a), 5.0 - std::sqrt(25.0 - r * r));
      const glm::dvec3 from = target + glm::dvec3(-std::cos(a), -std::sin(a), -0.3) * 4.0;
      LensBundle b;
      trace_lens(g, bk7_like(), ray(from, target - from, 6.0 * u(rng)), opt, b);
      check_bundle(b, "hemisphere cascade dT " + std::to_string(dT));
      if (::testing::Test::HasFatalFailure()) return;
      // Each internal ray yields at most one outgoing ray and one event; the cap bounds both.
      EXPECT_LE(b.rays.size(), 2u * opt.max_internal_rays + 2) << dT;
      EXPECT_LE(b.events.size(), 2u * opt.max_internal_rays + 2) << dT;
      worst = std::max(worst, b.rays.size() + b.events.size());
      limited += b.ray_limit_reached;
    }
    RecordProperty("worst_bundle_dT" + std::to_string(dT), static_cast<int>(worst));
    RecordProperty("ray_limit_reached_dT" + std::to_string(dT), limited);
  }
}

TEST(StabilityLens, TwoHundredMillimetrePathsNeedDoubleOrDifferences) {
  static_assert(std::is_same_v<decltype(PolarizedRay::optical_path_mm), double>,
                "the ray carries its optical path in double");
  // Two coherent rays after 200 mm of glass whose paths differ by Γ = 137.5 nm (a quarter wave at
  // 550 nm): the interference term cos(2πΓ/λ) = 0. Built the way a tracer builds paths — summing
  // 2000 segments of 0.1 mm × n — once in float and once in double.
  const double n = 1.5168, lambda_nm = 550.0, gamma_nm = 137.5;
  float pf1 = 0.0f, pf2 = 0.0f;
  double pd1 = 0.0, pd2 = 0.0;
  for (int i = 0; i < 2000; ++i) {
    pf1 += static_cast<float>(0.1 * n);
    pd1 += 0.1 * n;
  }
  pf2 = pf1 + static_cast<float>(gamma_nm * 1e-6);
  pd2 = pd1 + gamma_nm * 1e-6;
  const double two_pi = 2.0 * kPi;
  const double cos_float =
      std::cos(two_pi * (static_cast<double>(pf2) - static_cast<double>(pf1)) * 1e6 / lambda_nm);
  const double cos_double = std::cos(two_pi * (pd2 - pd1) * 1e6 / lambda_nm);
  // float at 303 mm has an ulp of 3e-5 mm = 30 nm: the 137.5 nm difference is quantised to a
  // multiple of 30 nm, so the phase is off by up to ~0.34 rad — a visible colour error. Show it:
  EXPECT_GT(std::fabs(cos_float), 0.05) << "float happened to be exact; the demonstration needs another Γ";
  // double: ulp 6e-14 mm = 6e-8 nm → |cos| < 1e-9.
  EXPECT_LT(std::fabs(cos_double), 1e-9);
  // Also the absolute phase: float's accumulated path drifts by many wavelengths over 2000 adds.
  const double drift_nm = std::fabs(static_cast<double>(pf1) - pd1) * 1e6;
  EXPECT_GT(drift_nm, lambda_nm / 10) << "float drift " << drift_nm << " nm";

  // The SML itself: a ray arriving with O_p = 200 mm leaves with exactly 200 mm more than the
  // same ray arriving with O_p = 0 (the lens adds n·S in double): to 1e-12 mm = 1e-6 nm.
  const LensGeometry g(spec(4.25, 4.3, -4.3, 0.3));
  LensTraceOptions opt;
  opt.max_depth = 3;
  PolarizedRay a = ray(g.front_vertex() + glm::dvec3(1.3, -0.7, -5.0), {0.05, 0.02, 1.0}, 0.4);
  PolarizedRay b = a;
  b.optical_path_mm = 200.0;
  LensBundle ba, bb;
  trace_lens(g, bk7_like(), a, opt, ba);
  trace_lens(g, bk7_like(), b, opt, bb);
  ASSERT_EQ(ba.rays.size(), bb.rays.size());
  for (std::size_t i = 0; i < ba.rays.size(); ++i)
    EXPECT_NEAR(bb.rays[i].optical_path_mm - ba.rays[i].optical_path_mm, 200.0, 1e-12);
}

}  // namespace
}  // namespace pmsim
