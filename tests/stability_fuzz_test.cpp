// Random fuzzed inputs, over a million rays in total: polarized spectral rays through SML lenses
// (random geometry among the degenerate and the paper's lens, any origin and direction, any dT,
// Fresnel or Schlick, TIR stopped or split) and plane waves through crystal plates (any mineral
// of the library, any orientation, thickness from 1 nm to 100 mm, directions down to 1e-9 of
// grazing). Nothing may come out NaN or Inf; lenses keep their energy balance and plates are
// passive. Timing is printed, never asserted.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/plate.h"
#include "core/lens/lens.h"
#include "core/lens/lens_tracer.h"

namespace pmsim {
namespace {

using Clock = std::chrono::steady_clock;

glm::dvec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  glm::dvec3 v;
  do v = {g(rng), g(rng), g(rng)};
  while (glm::length(v) < 1e-6);
  return glm::normalize(v);
}

TEST(StabilityFuzz, SixHundredThousandRandomRaysThroughSmlLensesStayFiniteAndBalanced) {
  std::vector<LensSpec> specs(4);
  specs[0].radius_mm = 4.25, specs[0].front_radius_mm = 4.3, specs[0].back_radius_mm = -4.3,
  specs[0].ledge_mm = 0.3;
  specs[1].radius_mm = 5, specs[1].front_radius_mm = 5, specs[1].back_radius_mm = 0, specs[1].ledge_mm = 0;
  specs[2].radius_mm = 5, specs[2].front_radius_mm = 5, specs[2].back_radius_mm = -5, specs[2].ledge_mm = 0;
  specs[3].radius_mm = 5, specs[3].front_radius_mm = 0, specs[3].back_radius_mm = 0, specs[3].ledge_mm = 2;
  std::vector<LensGeometry> lenses;
  for (const LensSpec& s : specs) lenses.emplace_back(s);
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int N = 600000;
  LensBundle b;
  std::size_t out_rays = 0, bad = 0, unbalanced = 0;
  const auto t0 = Clock::now();
  for (int i = 0; i < N; ++i) {
    const LensGeometry& g = lenses[i % lenses.size()];
    PolarizedRay r;
    // Half the rays aimed at the lens, half anywhere (misses, rays from inside, grazing).
    r.origin = g.center() + random_unit(rng) * (g.size_mm() * (0.01 + 3.0 * u(rng)));
    r.dir = (i & 1)
                ? random_unit(rng)
                : glm::normalize(g.center() + random_unit(rng) * g.aperture_radius_mm() * u(rng) - r.origin);
    if (!std::isfinite(r.dir.x)) r.dir = {0, 0, 1};
    glm::dvec3 a = glm::cross(r.dir, random_unit(rng));
    if (glm::length(a) < 1e-9) a = glm::cross(r.dir, glm::dvec3(1, 0, 0));
    r.pol = glm::normalize(a);
    r.wavelength_nm = 380.0 + 400.0 * u(rng);
    r.intensity = u(rng);
    r.optical_path_mm = 1000.0 * u(rng);
    LensTraceOptions opt;
    opt.max_depth = static_cast<int>(6 * u(rng));
    opt.tir = u(rng) < 0.5 ? TirMode::Stop : TirMode::Split;
    opt.fresnel = u(rng) < 0.8 ? FresnelModel::Exact : FresnelModel::Schlick;
    opt.max_internal_rays = 1024;
    // Dispersive glass index as a Sellmeier-like function of λ (kept local: no material library).
    const double l2 = r.wavelength_nm * r.wavelength_nm * 1e-6;
    const LensMedia m{std::sqrt(1.0 + 1.04 * l2 / (l2 - 0.006) + 0.23 * l2 / (l2 - 0.02)), 1.0, 1e-4};
    b.clear();
    trace_lens(g, m, r, opt, b);
    out_rays += b.rays.size();
    bool ok = std::isfinite(b.absorbed) && std::isfinite(b.filtered);
    for (const PolarizedRay& o : b.rays)
      ok = ok && std::isfinite(o.intensity) && std::isfinite(o.pol.x + o.pol.y + o.pol.z) &&
           std::isfinite(o.dir.x + o.dir.y + o.dir.z) && std::isfinite(o.optical_path_mm) &&
           std::isfinite(o.delta_rad) && std::isfinite(o.origin.x + o.origin.y + o.origin.z);
    for (const LensEvent& e : b.events) ok = ok && std::isfinite(e.intensity);
    if (!ok) {
      if (++bad < 5)
        ADD_FAILURE() << "non-finite output: lens " << i % lenses.size() << " origin (" << r.origin.x << ", "
                      << r.origin.y << ", " << r.origin.z << ") dir (" << r.dir.x << ", " << r.dir.y << ", "
                      << r.dir.z << ") λ " << r.wavelength_nm;
    }
    // Energy bookkeeping to 1e-12 relative (≤ ~1000 interactions of 1e-16 each).
    if (!(std::fabs(b.energy_defect()) <= 1e-12 * std::max(1e-300, b.incident) + 1e-300)) {
      if (++unbalanced < 5)
        ADD_FAILURE() << "energy defect " << b.energy_defect() << " of " << b.incident << " lens "
                      << i % lenses.size() << " origin (" << r.origin.x << ", " << r.origin.y << ", "
                      << r.origin.z << ") dir (" << r.dir.x << ", " << r.dir.y << ", " << r.dir.z << ")";
    }
  }
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("[ info ] %d SML rays (%zu outgoing) in %.2f s: %.2f M rays/s\n", N, out_rays, s, N / s / 1e6);
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(unbalanced, 0u);
}

TEST(StabilityFuzz, FourHundredThousandRandomPlaneWavesThroughPlatesStayFiniteAndPassive) {
  std::vector<const Crystal*> crystals;
  for (const std::string& name : mineral_names()) crystals.push_back(&find_mineral(name));
  static const Crystal extreme_u = Crystal::uniaxial_constant("extreme", 1.3, 2.9);
  static const Crystal extreme_b = Crystal::biaxial_constant("extreme-b", 1.3, 2.0, 2.9);
  static const Crystal zero = Crystal::uniaxial_constant("zero", 1.55, 1.55);
  crystals.push_back(&extreme_u);
  crystals.push_back(&extreme_b);
  crystals.push_back(&zero);
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int N = 400000;
  std::size_t bad = 0, gain = 0;
  const auto t0 = Clock::now();
  for (int i = 0; i < N; ++i) {
    const Crystal* c = crystals[i % crystals.size()];
    PlateSpec spec;
    spec.crystal = c;
    const glm::dvec3 z = random_unit(rng), x = random_unit(rng);
    spec.crystal_to_lab =
        c->symmetry() == CrystalSymmetry::Biaxial ? biaxial_orientation(x, z) : uniaxial_orientation(z);
    spec.thickness_um = std::pow(10.0, -3.0 + 8.0 * u(rng));  // 1 nm … 100 mm
    spec.n_outside = 1.0 + 0.8 * u(rng);
    spec.fresnel = u(rng) < 0.7;
    const double cz = (i % 7 == 0) ? std::pow(10.0, -9.0 * u(rng)) : u(rng) + 1e-12;
    const double sz = std::sqrt((1 - cz) * (1 + cz)), az = 2 * kPi * u(rng);
    const glm::dvec3 k{sz * std::cos(az), sz * std::sin(az), cz};
    const double nm = 380.0 + 400.0 * u(rng);
    const JonesMatrix J = plate_jones(spec, k, nm);
    bool ok = true;
    for (const complexd& v : {J.xx, J.xy, J.yx, J.yy})
      ok = ok && std::isfinite(v.real()) && std::isfinite(v.imag());
    if (!ok) {
      if (++bad < 5)
        ADD_FAILURE() << "non-finite Jones: " << c->name() << " d " << spec.thickness_um << " µm k (" << k.x
                      << ", " << k.y << ", " << k.z << ") λ " << nm << " n_out " << spec.n_outside;
      continue;
    }
    // Passive: no input polarization gains intensity (the plate neglects multiple reflections,
    // so |J·e|² ≤ 1 exactly up to rounding, plate.cpp); 1e-9 allows the biaxial iteration.
    // Asserted for the library's minerals with Fresnel faces (what the renderer uses). The
    // fictitious Δn = 1.6 crystals lie outside the plate model's first-order-in-birefringence
    // interface treatment (plate.h) and are checked for finiteness only; fresnel = false has its
    // own regression test below.
    if (c == &extreme_u || c == &extreme_b || !spec.fresnel) continue;
    for (double a : {0.0, 0.785398, 1.570796})
      for (complexd ph : {complexd(1, 0), complexd(0, 1)}) {
        const JonesVector e{std::cos(a), std::sin(a) * ph};
        if ((J * e).intensity() > 1.0 + 1e-9 && ++gain < 5)
          ADD_FAILURE() << "gain " << (J * e).intensity() << ": " << c->name() << " d " << spec.thickness_um
                        << " µm k (" << k.x << ", " << k.y << ", " << k.z << ") λ " << nm;
      }
  }
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("[ info ] %d plate Jones matrices in %.2f s: %.2f M/s\n", N, s, N / s / 1e6);
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(gain, 0u);
}

// REGRESSION (core/crystal/plate.cpp, owner: crystal): with PlateSpec::fresnel = false the plate
// is documented as lossless ("decomposed on the mode D directions and recomposed"), but for
// oblique waves the two projected mode directions are not orthogonal, and decomposing on that
// skew basis and re-adding with a relative phase is not unitary: the Jones matrix gains energy.
// Found by the fuzz sweep: calcite, θ_air ≈ 1.46 rad, d ≈ 74 µm: |J·e|² = 1.094 for the worst
// input polarization; muscovite 1.02, augite 1.012. The renderer's samples use fresnel = true
// (passive to 1e-9, asserted above), so images are not affected; compensator plates at normal
// incidence neither. Fix: project onto the dual basis on entry and the mode basis on exit (as the
// Fresnel branch does), or orthonormalise. Expected to fail until then.
TEST(StabilityFuzz, PlateWithoutFresnelFacesIsPassiveAtObliqueIncidence) {
  const Crystal& calcite = find_mineral("calcite");
  double worst = 0.0;
  std::string where;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      const double ta = kPi * i / 12, pa = 2 * kPi * j / 12;
      PlateSpec spec;
      spec.crystal = &calcite;
      spec.crystal_to_lab =
          uniaxial_orientation({std::sin(ta) * std::cos(pa), std::sin(ta) * std::sin(pa), std::cos(ta)});
      spec.thickness_um = 74.0;
      spec.fresnel = false;
      for (double theta : {0.5, 1.0, 1.46})
        for (double az : {0.0, 1.0, 2.0}) {
          const glm::dvec3 k{std::sin(theta) * std::cos(az), std::sin(theta) * std::sin(az), std::cos(theta)};
          const JonesMatrix J = plate_jones(spec, k, 550.0);
          for (double a = 0; a < kPi; a += kPi / 16)
            for (complexd ph : {complexd(1, 0), complexd(0, 1)}) {
              const double g = (J * JonesVector{std::cos(a), std::sin(a) * ph}).intensity();
              if (g > worst) {
                worst = g;
                where = "optic axis polar " + std::to_string(ta) + " az " + std::to_string(pa) + ", k θ " +
                        std::to_string(theta) + " az " + std::to_string(az);
              }
            }
        }
    }
  // Lossless means |J·e|² ≤ 1 to rounding (1e-12).
  EXPECT_LE(worst, 1.0 + 1e-12) << "worst gain at " << where;
}

}  // namespace
}  // namespace pmsim
