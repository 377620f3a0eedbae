// The grain-mount image as a progressive render (issue 12): a quarter-size preview first, then
// full passes that stop once the split-half error estimate is below the tolerance, with the
// estimate on every image after the first two passes; pixels no ray of which can reach a fragment
// are the empty field exactly (not a noisy estimate of it).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/specimen_fixture.h"

using namespace specimen_test;

TEST(SpecimenProgressive, PreviewFirstThenPassesWithAnEstimateAndAStopAtTheTolerance) {
  // A tolerance this one-fragment image reaches in tens of passes (its estimate falls from 6.9 after
  // two passes to ~2.5 after 128: the Becke line's light converges slowly).
  constexpr double kTolerance = 4.0;
  const auto s = make_specimen(OneFragment{});
  auto o = mono_view(10.0, 256);
  o.preview_factor = 4;
  o.tolerance_de2000 = kTolerance;
  std::vector<pmsim::RenderImage> seen;
  const auto img = pmsim::render_plane_light(*s, o, [&](const pmsim::RenderImage& i) { seen.push_back(i); });
  ASSERT_GE(seen.size(), 3u);
  // The preview: full size, one path per 4×4 pixels, no estimate.
  EXPECT_EQ(seen[0].passes, 1);
  EXPECT_EQ(seen[0].width, 160);
  EXPECT_DOUBLE_EQ(seen[0].samples_per_pixel, 1.0 / 16);
  EXPECT_FALSE(seen[0].error_estimate);
  // The first full pass has no second half to compare with; from the second on, an estimate
  // (an odd pass shows the last even pass's).
  EXPECT_FALSE(seen[1].error_estimate);
  for (std::size_t k = 2; k < seen.size(); ++k) ASSERT_TRUE(seen[k].error_estimate) << k;
  for (std::size_t k = 1; k < seen.size(); ++k) EXPECT_EQ(seen[k].passes, int(k) + 1);
  // Stopped at the tolerance, before the 256 paths (128 passes of 2 strata): converged, with the
  // estimate below it, and the last estimate before it above it.
  ASSERT_TRUE(img.error_estimate);
  std::printf("stopped after %d passes, %.0f paths a pixel, estimate %.3f\n", img.passes, img.samples_per_pixel,
              *img.error_estimate);
  EXPECT_TRUE(img.converged);
  for (std::size_t k = 2; k < seen.size(); k += 2) std::printf(" %.2f", *seen[k].error_estimate);
  std::printf("\n");
  EXPECT_LT(*img.error_estimate, kTolerance);
  EXPECT_LT(img.samples_per_pixel, 256.0);
  const pmsim::RenderImage& before = seen[seen.size() - 3];
  ASSERT_TRUE(before.error_estimate);
  EXPECT_GE(*before.error_estimate, kTolerance);
  // The preview already shows the fragment: mean Y over its inside within 0.1 of the final
  // image's (one path a pixel, 4×4 averaged by the bilinear spread, against hundreds).
  const auto d = signed_distance(*s, o);
  EXPECT_NEAR(band_mean(seen[0], d, 10, 100), band_mean(img, d, 10, 100), 0.1);
}

TEST(SpecimenProgressive, FarFromEveryFragmentThePixelIsTheEmptyFieldExactly) {
  // 2 µm pixels over 320 µm: the 100 µm fragment in the middle, liquid to 160 µm from its centre.
  const auto s = make_specimen(OneFragment{});
  auto o = mono_view(0.0, 8);
  o.um_per_px = 2.0;
  const auto img = pmsim::render_plane_light(*s, o);
  const auto d = signed_distance(*s, o);
  int far = 0, near_noisy = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    // Beyond 60 µm of liquid the focused cone (NA 0.25, at most ~25 µm wide in the layer) misses
    // the fragment: exactly 1 (Y of the empty field by definition), not 1 ± noise.
    if (d[i] < -60.0) {
      ++far;
      EXPECT_EQ(img.xyz[3 * i + 1], 1.0f) << i;
    }
    if (d[i] > -4.0 && d[i] < 0.0 && img.xyz[3 * i + 1] != 1.0f) ++near_noisy;
  }
  EXPECT_GT(far, 10000);
  EXPECT_GT(near_noisy, 100) << "pixels at the outline are traced";
}

// Issue 21: `converged` means the estimate is below the tolerance and nothing else. A render
// that its pass cap ends first (2 passes, a tolerance no noisy estimate meets) is not converged
// and says it stopped at the cap; a tiny image keeps it cheap.
TEST(SpecimenProgressive, StoppedAtThePassCapIsNotConverged) {
  const auto s = make_specimen(OneFragment{});
  auto o = mono_view(10.0, 4);  // 2 passes of 2 strata (inner cone and annulus)
  o.width = o.height = 24;
  o.um_per_px = 5.0;  // 120 µm: the whole 100 µm fragment, its outline traced
  o.tolerance_de2000 = 1e-9;
  std::vector<pmsim::RenderImage> seen;
  const auto img = pmsim::render_plane_light(*s, o, [&](const pmsim::RenderImage& i) { seen.push_back(i); });
  ASSERT_EQ(img.passes, 2) << "the cap: 2 passes, the first two an estimate is made from";
  ASSERT_TRUE(img.error_estimate);
  EXPECT_GE(*img.error_estimate, o.tolerance_de2000);
  EXPECT_FALSE(img.converged);
  EXPECT_EQ(img.stopped, "cap");
  // While it runs, an image has no reason to have stopped.
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].stopped, "");
  EXPECT_FALSE(seen[0].converged);
}
