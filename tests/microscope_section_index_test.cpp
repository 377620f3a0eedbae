// The section map's lookup grid must give exactly the exhaustive nearest-grain answer (the grid
// only prunes grains that provably cannot be nearest in a cell).
#include <gtest/gtest.h>

#include <random>

#include "core/microscope/section_map.h"

using namespace pmsim;

namespace {

void expect_grid_equals_exhaustive(const std::string& name) {
  const auto m = load_section(name);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(-0.5 * m->width_mm, 0.5 * m->width_mm);
  std::uniform_real_distribution<double> uy(-0.5 * m->height_mm, 0.5 * m->height_mm);
  int mismatches = 0;
  for (int i = 0; i < 200000; ++i) {
    const glm::dvec2 p{ux(rng), uy(rng)};
    const int d = m->domain_at(p);
    if (d == SectionMap::kMediumDomain) continue;  // a crack: no grain to compare
    mismatches += m->grain_label(d) != m->nearest_grain_exhaustive(p) + 1;
  }
  // Same distances computed by the same function, candidates in the same order: exact agreement.
  EXPECT_EQ(mismatches, 0) << name;
}

}  // namespace

TEST(SectionIndex, GridLookupEqualsExhaustiveSearchEverywhere) {
  expect_grid_equals_exhaustive("granite_hand_placed");  // the hand-placed file
}
