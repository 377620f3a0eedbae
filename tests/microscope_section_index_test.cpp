// The section map's lookup grid must give exactly the exhaustive nearest-grain answer (the grid
// only prunes grains that provably cannot be nearest in a cell).
#include <gtest/gtest.h>

#include <random>

#include "core/microscope/section_map.h"

using namespace pmsim;

TEST(SectionIndex, GridLookupEqualsExhaustiveSearchEverywhere) {
  const auto indexed = load_section("granite");
  // A copy with one more (never nearest: weight 1e-6, far away) grain: its grid no longer
  // matches its grains, so it searches all of them.
  SectionMap exhaustive = *indexed;
  SectionGrain far = exhaustive.grains.front();
  far.seed = {1e6, 1e6};
  far.weight = 1e-6;
  exhaustive.grains.push_back(far);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.5, 2.5);  // beyond the grid's ±2 too
  int mismatches = 0;
  for (int i = 0; i < 200000; ++i) {
    const glm::dvec2 p{u(rng), u(rng)};
    mismatches += indexed->domain_at(p) != exhaustive.domain_at(p);
  }
  // Same distances computed by the same function, candidates in the same order: exact agreement.
  EXPECT_EQ(mismatches, 0);
}
