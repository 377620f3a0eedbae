// Relief from traced light (issue 12): the outline's contrast grows with |n − n_liquid|, a fragment
// matching the liquid at every wavelength leaves the field uniform, and calcite's relief depends
// on which of its indices the polarizer's vibration meets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/base/units.h"
#include "tests/specimen_fixture.h"

using namespace specimen_test;

namespace {

// Relief as the light missing around the outline: the mean of max(0, 1 − I) over the pixels from
// 20 µm outside to 30 µm inside the true outline, in focus (focus_um = 0); the empty field is 1.
// Geometrically a surface element is dark where its slope deflects the ray beyond what the
// apertures accept, and the steeper-than-threshold rim widens as |n − n_liquid| grows.
double outline_contrast(const OneFragment& f, double stage_rad = 0.0) {
  const auto s = make_specimen(f);
  auto o = mono_view(0.0, 32);
  o.stage_rad = stage_rad;
  const auto img = pmsim::render_plane_light(*s, o);
  const auto d = signed_distance(*s, o);
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] > -20.0 && d[i] < 30.0) {
      sum += std::max(0.0, 1.0 - img.xyz[3 * i + 1]);
      ++n;
    }
  return sum / n;
}

}  // namespace

// Each step of n doubles or more the index difference; the contrast must rise by 20 % at least
// (band-mean noise ≈ 0.01 against contrasts of 0.05–0.5).
TEST(SpecimenRelief, OutlineContrastGrowsWithIndexDifference) {
  double previous = 0.0;
  for (double n : {1.56, 1.60, 1.70}) {
    OneFragment f;
    f.n_fragment = n;
    const double c = outline_contrast(f);
    std::printf("n %.2f in 1.54: outline contrast %.4f\n", n, c);
    EXPECT_GT(c, 1.2 * previous) << "n = " << n;
    previous = c;
  }
}

// n = n_liquid at every λ: no interface refracts or reflects (η = 1), so every pixel sees what
// the empty field sees. The remaining spread is the sampling noise of the stack alone, whose
// Fresnel transmission varies by < 1 % across the 0.03-NA cone of the lit rays.
TEST(SpecimenRelief, MatchedIndexGivesAUniformField) {
  OneFragment f;
  f.n_fragment = 1.54;
  f.n_liquid = 1.54;
  const auto s = make_specimen(f);
  const auto o = mono_view(0.0, 32);
  const auto img = pmsim::render_plane_light(*s, o);
  double lo = 1e9, hi = -1e9;
  for (std::size_t i = 1; i < img.xyz.size(); i += 3) lo = std::min(lo, double(img.xyz[i])), hi = std::max(hi, double(img.xyz[i]));
  std::printf("matched: Y in [%.5f, %.5f]\n", lo, hi);
  EXPECT_GT(lo, 0.99);
  EXPECT_LT(hi, 1.01);
  const auto d = signed_distance(*s, o);
  EXPECT_NEAR(band_mean(img, d, 0, 8), band_mean(img, d, -8, 0), 0.002);
  // The same fragment 0.06 above the liquid is clearly outlined: the test can fail.
  f.n_fragment = 1.60;
  EXPECT_GT(outline_contrast(f), 0.05);
}

// Calcite (no 1.658, ne 1.486) in 1.54 with its optic axis horizontal. Polarizer E–W: with c
// along E–W the vibration meets ne (Δn = −0.054), with the stage turned 90° it meets no
// (Δn = +0.118): the relief must differ clearly. Factor 1.15: the mean over ~10⁴ pixels has a
// noise below 0.005 against contrasts of ~0.25 (isotropic n = 1.60, Δn = 0.06, gives 0.25 too).
TEST(SpecimenRelief, CalciteReliefChangesWithTheVibrationDirection) {
  OneFragment f;
  f.crystal = pmsim::Crystal::uniaxial_constant("calcite", 1.658, 1.486);
  f.n_liquid = 1.54;
  // Crystal Z (the optic axis) along lab x.
  f.orientation = glm::dmat3(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));
  const double along_ne = outline_contrast(f, 0.0);
  const double along_no = outline_contrast(f, pmsim::kPi / 2);
  std::printf("calcite: contrast with vibration along ne %.4f, along no %.4f\n", along_ne, along_no);
  EXPECT_GT(along_no, 1.15 * along_ne);
}

// The anisotropic index is the indicatrix's: the fringe sense of calcite flips with the
// vibration, ne below the liquid (fringe out when focusing up), no above it (fringe in).
TEST(SpecimenRelief, CalciteBeckeLineFollowsTheIndexOfTheVibration) {
  OneFragment f;
  f.crystal = pmsim::Crystal::uniaxial_constant("calcite", 1.658, 1.486);
  f.orientation = glm::dmat3(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));
  const auto s = make_specimen(f);
  for (double stage : {0.0, pmsim::kPi / 2}) {
    auto o = mono_view(20.0, 32);
    o.stage_rad = stage;
    const auto img = pmsim::render_plane_light(*s, o);
    const auto d = signed_distance(*s, o);
    double peak = 0.0, where = 0.0;
    for (double a = -14; a < 14; a += 2) {
      const double m = band_mean(img, d, a, a + 2);
      if (m > peak) peak = m, where = a + 1;
    }
    std::printf("calcite stage %.0f°: brightest band %.2f at %+.0f µm\n", stage * 180 / pmsim::kPi, peak, where);
    if (stage == 0.0)
      EXPECT_LT(where, 0.0) << "ne 1.486 < 1.54: the fringe goes out into the liquid";
    else
      EXPECT_GT(where, 0.0) << "no 1.658 > 1.54: the fringe goes into the fragment";
  }
}
