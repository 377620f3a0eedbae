// Inclusions in a grain (SectionGrain::InclusionSet): their area, their limit, their domains and
// the reader's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/microscope/section_map.h"

using namespace pmsim;

namespace {

nlohmann::json garnet_with_inclusions(double size_mm, double spacing_mm) {
  return {{"type", "section"},
          {"size_mm", {3.0, 3.0}},
          {"grains",
           {{{"mineral", "almandine"},
             {"centre_mm", {0.0, 0.0}},
             {"size_mm", 2.0},
             {"euler_deg", {0.0, 0.0, 0.0}},
             {"inclusions",
              {{"mineral", "quartz"},
               {"size_mm", size_mm},
               {"aspect", 2.0},
               {"spacing_mm", spacing_mm},
               {"trail_spacing_mm", 0.08},
               {"fraction", 0.5},
               {"within", 0.8},
               {"euler_deg", {{0, 0, 0}, {30, 60, 90}, {200, 10, 40}}}}}}}}};
}

}  // namespace

TEST(SectionInclusions, CoverTheirExpectedShareInsideTheirLimitAndNothingOutside) {
  const SectionMap m = section_from_json(garnet_with_inclusions(0.04, 0.1), "inclusions");
  ASSERT_EQ(m.grains.size(), 1u);
  const SectionGrain& g = m.grains[0];
  ASSERT_TRUE(g.inclusions);
  EXPECT_EQ(m.domain_count(), g.first_inclusion_domain() + 3);
  const double R = g.semi_major_mm;  // an equant garnet: a disc of radius R, s = r/R
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  long inner = 0, inner_hits = 0, ring = 0, ring_hits = 0;
  for (int i = 0; i < 400000; ++i) {
    const glm::dvec2 p{R * u(rng), R * u(rng)};
    const double r = std::hypot(p.x, p.y) / R;
    const int d = m.domain_at(p);
    const bool hit = m.domain_part(d).inclusion >= 0;
    if (hit) {
      EXPECT_EQ(m.mineral_of_domain(d), "quartz");
      EXPECT_EQ(m.grain_label(d), 1);
      EXPECT_LT(m.domain_part(d).inclusion, 3);
    }
    if (r < 0.7) {
      ++inner;
      inner_hits += hit;
    } else if (r > 0.82 && r < 0.95) {
      ++ring;
      ring_hits += hit;
    }
  }
  // Each 0.1 × 0.08 mm cell holds an ellipse of 0.04 × 0.02 mm with probability 0.5: a share of
  // 0.5·(π/4)·0.04·0.02/0.008 = 0.0393. About 190 cells lie within 0.7 R: the occupied count is
  // binomial with a relative standard deviation of √(0.5/(0.5·190)) ≈ 7 %; 25 % is 3.5 σ.
  const double expected = 0.5 * 0.25 * M_PI * 0.04 * 0.02 / (0.1 * 0.08);
  EXPECT_NEAR(static_cast<double>(inner_hits) / inner, expected, 0.25 * expected);
  // Beyond `within` (0.8 of the way to the rim) the garnet is clear.
  EXPECT_GT(ring, 10000);
  EXPECT_EQ(ring_hits, 0);
}

TEST(SectionInclusions, RefuseInclusionsLargerThanTheirSpacing) {
  try {
    (void)section_from_json(garnet_with_inclusions(0.2, 0.1), "bad.json");
    FAIL() << "an inclusion longer than its site spacing was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("spacing_mm"), std::string::npos) << e.what();
  }
}
