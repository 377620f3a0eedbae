// The Becke line out of traced light (issue 12): an isotropic fragment of n = 1.60 in a liquid of
// 1.54 and of 1.66, focused above and below its mid-plane. The bright fringe is light crowded by
// refraction at the fragment's inclined edge; it lies on the side of the higher index when the
// objective is raised (the lens effect of the edge: its rays converge above the boundary toward
// the denser medium), and outside/inside swap with the liquid.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/specimen_fixture.h"

using namespace specimen_test;

namespace {

struct Fringe {
  double peak_side = 0.0;       // signed distance of the brightest 2 µm band within 14 µm
  double peak = 0.0;            // its mean relative intensity
  double centroid_um = 0.0;     // distance from the outline of the excess light (I > 1) on that side
};

Fringe fringe(double n_liquid, double focus_um) {
  OneFragment f;
  f.n_liquid = n_liquid;
  const auto s = make_specimen(f);
  const auto o = mono_view(focus_um, 32);
  const auto img = pmsim::render_plane_light(*s, o);
  const auto d = signed_distance(*s, o);
  Fringe r;
  std::printf("n_liquid %.2f focus %+5.1f µm:", n_liquid, focus_um);
  for (double a = -14; a < 14; a += 2) {
    const double m = band_mean(img, d, a, a + 2);
    std::printf(" %.2f", m);
    if (m > r.peak) r.peak = m, r.peak_side = a + 1;
  }
  // The window ends 12 µm from the outline: further in, the light the flat top focuses is not
  // the edge's fringe.
  double w = 0.0, wd = 0.0;
  for (double a = 0; a < 12; a += 1) {
    const double lo = r.peak_side > 0 ? a : -a - 1;
    const double excess = std::max(0.0, band_mean(img, d, lo, lo + 1) - 1.0);
    w += excess;
    wd += excess * (a + 0.5);
  }
  r.centroid_um = w > 0 ? wd / w : 0.0;
  std::printf("  peak %.2f at %+.0f µm, excess centroid %.1f µm\n", r.peak, r.peak_side, r.centroid_um);
  return r;
}

}  // namespace

// Brightness threshold 1.1: the empty field is 1 (exposure reference) with a noise of the band
// means below 0.02 (≥ 300 pixels × 32 samples); a fringe is light brought in from elsewhere.
TEST(SpecimenBeckeLine, HigherIndexFragmentFringeMovesInWhenFocusingUp) {
  const Fringe up = fringe(1.54, 20.0), down = fringe(1.54, -20.0);
  EXPECT_GT(up.peak_side, 0.0) << "focused up, the fringe lies inside the fragment (n 1.60 > 1.54)";
  EXPECT_LT(down.peak_side, 0.0) << "focused down, outside";
  EXPECT_GT(up.peak, 1.1);
  EXPECT_GT(down.peak, 1.1);
}

TEST(SpecimenBeckeLine, HigherIndexLiquidReversesTheFringe) {
  const Fringe up = fringe(1.66, 20.0), down = fringe(1.66, -20.0);
  EXPECT_LT(up.peak_side, 0.0) << "focused up, the fringe moves into the liquid (1.66 > 1.60)";
  EXPECT_GT(down.peak_side, 0.0);
  EXPECT_GT(up.peak, 1.1);
  EXPECT_GT(down.peak, 1.1);
}

// The fringe is the converging (or diverging) light of the edge seen in a plane further from
// it: its distance from the outline grows with the defocus. The centroid of the excess light is
// measured in 1 µm bands; 10 µm more defocus must move it by more than the band width.
TEST(SpecimenBeckeLine, FringeDistanceGrowsWithDefocus) {
  const Fringe near_up = fringe(1.54, 10.0), far_up = fringe(1.54, 30.0);
  EXPECT_GT(far_up.centroid_um, near_up.centroid_um + 1.0);
  const Fringe near_down = fringe(1.54, -10.0), far_down = fringe(1.54, -30.0);
  EXPECT_GT(far_down.centroid_um, near_down.centroid_um + 1.0);
}
