// sample.orientation_seed (core/microscope/section_reorient.h): a new specimen of the same rock —
// the same grains in the same places, each in a new orientation drawn uniformly over the rotations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/base/input_error.h"
#include "core/microscope/map_section.h"
#include "core/microscope/scene_check.h"
#include "core/microscope/section_map.h"
#include "core/microscope/section_reorient.h"

using namespace pmsim;

// Haar measure in Bunge angles: φ1, φ2 uniform on [0°, 360°), cos Φ uniform on [−1, 1]. Over
// N = 20000 draws the means' standard errors are 360/√(12N) = 0.73° and 1/√(3N) = 0.0041; the
// tolerances are 5σ (a test that fails by chance once in ~10⁶ runs, and catches Φ drawn uniform
// in angle, whose mean cos Φ over [0, π] is 0 too but whose mean cos² Φ is 1/2, not 1/3).
TEST(SectionReorient, EulerAnglesAreUniformOverRotations) {
  constexpr int n = 20000;
  double phi1 = 0, phi2 = 0, c = 0, c2 = 0;
  for (int i = 0; i < n; ++i) {
    const auto e = uniform_euler_deg(11, std::uint64_t(i));
    ASSERT_GE(e[0], 0.0);
    ASSERT_LT(e[0], 360.0);
    ASSERT_GE(e[1], 0.0);
    ASSERT_LE(e[1], 180.0);
    phi1 += e[0], phi2 += e[2];
    const double cp = std::cos(e[1] * std::numbers::pi / 180.0);
    c += cp, c2 += cp * cp;
  }
  EXPECT_NEAR(phi1 / n, 180.0, 5 * 0.73);
  EXPECT_NEAR(phi2 / n, 180.0, 5 * 0.73);
  EXPECT_NEAR(c / n, 0.0, 5 * 0.0041);
  // Var(cos²Φ) = 1/5 − 1/9 = 4/45 for uniform cos Φ: σ of the mean 0.0021.
  EXPECT_NEAR(c2 / n, 1.0 / 3.0, 5 * 0.0021);
}

TEST(SectionReorient, SameGrainsNewOrientationsReproducibly) {
  const auto file = load_section("granite_hand_placed");
  const auto a = load_section("granite_hand_placed", 7), b = load_section("granite_hand_placed", 7), c = load_section("granite_hand_placed", 8);
  EXPECT_EQ(a, b) << "one seed, one section (cached)";
  ASSERT_EQ(a->grains.size(), file->grains.size());
  int changed = 0, differ_between_seeds = 0;
  for (std::size_t i = 0; i < a->grains.size(); ++i) {
    EXPECT_EQ(a->grains[i].mineral, file->grains[i].mineral);
    EXPECT_EQ(a->grains[i].centre_mm, file->grains[i].centre_mm);
    const double d1 = std::abs(a->grains[i].orientation[2].z - file->grains[i].orientation[2].z);
    const double d2 = std::abs(a->grains[i].orientation[2].z - c->grains[i].orientation[2].z);
    changed += d1 > 1e-6, differ_between_seeds += d2 > 1e-6;
  }
  // A redrawn Z axis keeps its z component to 1e-6 with probability ~1e-6 a grain.
  EXPECT_EQ(changed, int(a->grains.size()));
  EXPECT_EQ(differ_between_seeds, int(a->grains.size()));
}

TEST(SectionReorient, SceneCheckRefusesNegativeSeedsAndMaps) {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.sample.orientation_seed = 3;
  EXPECT_NO_THROW(check_scene(s));
  s.sample.orientation_seed = -1;
  try {
    check_scene(s, "x.json");
    FAIL() << "a negative seed must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "sample.orientation_seed");
    EXPECT_EQ(e.value, "-1");
  }
  s.sample.orientation_seed = 3;
  s.sample.section = "quartzite_example.ctf";
  try {
    check_scene(s, "x.json");
    FAIL() << "an EBSD map's orientations are measured: no seed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "sample.orientation_seed");
  }
}
