// Syntaxial overgrowth cement (core/texture/overgrowth_cement.h, issue 22's "quartz overgrowth
// cement"): the form it grows toward, the calibration of its amount, and its lookup.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/crystal/crystal_polyhedron.h"
#include "core/crystal/euler_angles.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/texture/overgrowth_cement.h"
#include "core/texture/rock_recipe.h"

namespace pmsim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Quartz's form: the hexagonal prism m{10-10}, faces parallel to c, and the rhombohedra r{10-11}
// and z{01-11}, whose normals lie at ρ from c with tan ρ = 2c / (√3·a) (the hexagonal setting's
// interplanar geometry: d(hkl)⁻² = 4(h² + hk + k²)/(3a²) + l²/c², so the (h0l) normal makes
// tan ρ = (2/√3)·(c/a)·h/l with c, a the cell edges): 51.78° for a = 4.9137, c = 5.4047 Å, the
// r ∧ c = 51°47′ of the mineralogy texts (Deer, Howie & Zussman 2013). Every face touches the
// unit ball: gauge 1 along its normal, and no point of the ball is outside (gauge ≤ |x|).
// Tolerance 1e-9°: the normals come from the reciprocal basis in double.
TEST(OvergrowthCement, QuartzGrowsTowardItsPrismAndRhombohedra) {
  const MineralCrystallography* mc = find_mineral_crystallography("quartz");
  ASSERT_NE(mc, nullptr);
  const CrystalPolyhedron f = overgrowth_unit_form(*mc);
  ASSERT_EQ(f.normals.size(), 18u);
  const double rho = std::atan(2.0 * 5.4047 / (std::sqrt(3.0) * 4.9137)) * 180.0 / kPi;
  EXPECT_NEAR(rho, 51.78, 0.005);
  int prism = 0, rhomb = 0;
  for (std::size_t i = 0; i < f.normals.size(); ++i) {
    const double a = std::acos(std::abs(f.normals[i].z)) * 180.0 / kPi;  // from c = e3 (lattice.h)
    if (std::abs(a - 90.0) < 1e-9) ++prism;
    if (std::abs(a - rho) < 1e-9) ++rhomb;
    EXPECT_DOUBLE_EQ(f.support_mm[i], 1.0);
    EXPECT_NEAR(gauge(f, f.normals[i]), 1.0, 1e-15);
  }
  EXPECT_EQ(prism, 6);
  EXPECT_EQ(rhomb, 12);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n;
  for (int k = 0; k < 1000; ++k) {
    const glm::dvec3 x = glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
    EXPECT_LE(gauge(f, x), 1.0 + 1e-15);
  }
  // The apex of the dipyramid on c: 1 / cos ρ from the centre, the form's farthest vertex.
  EXPECT_NEAR(f.circumradius_mm, 1.0 / std::cos(rho * kPi / 180.0), 1e-9);
}

// The calibration's scale is the quantile of the pores' reaches: exactly k of the points reach
// within it, infinite reaches are never cement, and more cement than the reachable pores is
// refused.
TEST(OvergrowthCement, TheScaleIsTheQuantileOfThePoresReaches) {
  std::vector<double> reach;
  for (int i = 0; i < 100; ++i) reach.push_back(0.5 + 0.01 * ((i * 37) % 100));  // 0.5 … 1.49, shuffled
  reach.push_back(std::numeric_limits<double>::infinity());
  const double h = overgrowth_scale_for(reach, 1000, 0.03);  // 30 of 1000 points
  EXPECT_DOUBLE_EQ(h, 0.5 + 0.01 * 29);
  int n = 0;
  for (const double r : reach) n += r <= h ? 1 : 0;
  EXPECT_EQ(n, 30);
  EXPECT_DOUBLE_EQ(overgrowth_scale_for(reach, 1000, 0.1), 1.49);  // all 100 finite reaches
  EXPECT_THROW((void)overgrowth_scale_for(reach, 1000, 0.102), std::invalid_argument);
  // Under half a point of cement: a positive scale the section reader takes, below every reach.
  const double none = overgrowth_scale_for(reach, 1000, 0.0004);
  EXPECT_GT(none, 0.0);
  EXPECT_LT(none, 0.5);
}

// The grid's owner is the exhaustive search's, ties included, over random grains in random
// orientations: cement goes to the face that arrives first, r·(H·gauge − 1), and only inside a form.
TEST(OvergrowthCement, GridOwnerEqualsTheExhaustiveSearch) {
  const CrystalPolyhedron unit = overgrowth_unit_form(*find_mineral_crystallography("quartz"));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<GrainOvergrowth> grains;
  for (int i = 0; i < 60; ++i) {
    const double r = 0.1 + 0.2 * u(rng), h = 0.8 + 0.4 * u(rng);
    const glm::dmat3 L = crystal_to_sample_from_bunge({2 * kPi * u(rng), std::acos(2 * u(rng) - 1), 2 * kPi * u(rng)});
    grains.push_back({{4 * u(rng) - 2, 4 * u(rng) - 2, r * (u(rng) - 0.5)}, r, h, overgrowth_form(unit, L, r, h)});
  }
  const OvergrowthCement cement(grains, 4.0, 4.0);
  int cemented = 0;
  for (int j = 0; j < 200; ++j)
    for (int i = 0; i < 200; ++i) {
      const glm::dvec2 p{-2.0 + 0.02 * (i + 0.5), -2.0 + 0.02 * (j + 0.5)};
      const int o = cement.owner(p);
      ASSERT_EQ(o, cement.owner_exhaustive(p)) << p.x << ", " << p.y;
      if (o < 0) continue;
      ++cemented;
      EXPECT_LE(overgrowth_reach(grains[std::size_t(o)], p), grains[std::size_t(o)].habit_scale);
    }
  EXPECT_GT(cemented, 1000);
}

// The recipe keys' limits, each refusal naming the file and the key: an overgrowth on a grain
// that is not a detrital ball, cement in a rock without pores, a dust line of an anisotropic
// mineral (its specks would need orientations), and more cement than the pores can hold.
TEST(OvergrowthCement, RecipeRefusesWhatCannotGrow) {
  nlohmann::json base;
  {
    std::ifstream f(rock_recipe_path("sandstone"));
    base = nlohmann::json::parse(f);
  }
  ASSERT_TRUE(base["phases"][0].contains("overgrowth"));
  const std::string path = (std::filesystem::temp_directory_path() / "pmsim_overgrowth_recipe.json").string();
  const auto refused = [&](const nlohmann::json& j, const std::string& key, const std::string& words) {
    {
      std::ofstream f(path);
      f << j.dump(2);
    }
    try {
      (void)read_rock_recipe(path);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(path), std::string::npos) << m;
      EXPECT_NE(m.find(key), std::string::npos) << m;
      EXPECT_NE(m.find(words), std::string::npos) << m;
    }
  };
  nlohmann::json j = base;
  j["phases"][0].erase("shape");
  refused(j, "overgrowth", "rounded detrital grain");
  j = base;
  j.erase("matrix");
  refused(j, "overgrowth", "no matrix");
  j = base;
  j["phases"][0]["overgrowth"]["dust"]["mineral"] = "muscovite";
  refused(j, "mineral", "isotropic");
  j = base;
  j["phases"][0]["overgrowth"]["cement_percent"] = 25;
  refused(j, "phases", "over 100");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace pmsim
