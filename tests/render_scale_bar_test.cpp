// The scale bar: a round length whose drawn pixels match the image scale.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/scale_bar.h"

namespace pmsim {
namespace {

TEST(ScaleBar, PicksTheLongestOneTwoFiveLengthThatFits) {
  // 10× objective, field number 20, 512 px: 2 mm / 512 px; a quarter of the width is 0.5 mm.
  const ScaleBar b = choose_scale_bar(2.0 / 512, 512);
  EXPECT_DOUBLE_EQ(b.length_mm, 0.5);
  EXPECT_EQ(b.label, "500 um");
  EXPECT_NEAR(b.length_px, 128.0, 1e-9);
  // 4×: 5 mm field; a quarter is 1.25 mm → 1 mm.
  const ScaleBar c = choose_scale_bar(5.0 / 512, 512);
  EXPECT_DOUBLE_EQ(c.length_mm, 1.0);
  EXPECT_EQ(c.label, "1 mm");
  // 40×: 0.5 mm field; a quarter is 125 µm → 100 µm.
  EXPECT_EQ(choose_scale_bar(0.5 / 512, 512).label, "100 um");
}

TEST(ScaleBar, BurnedBarIsAsLongAsItsLength) {
  const int w = 512, h = 512;
  std::vector<float> rgb(static_cast<std::size_t>(w) * h * 3, 0.25f);
  const ScaleBar b = choose_scale_bar(2.0 / 512, w);
  burn_scale_bar(rgb, w, h, b);
  // The longest run of white pixels on any row is the bar: its length in pixels, ±0.5 px of
  // rounding of length_px.
  int longest = 0;
  for (int y = 0; y < h; ++y) {
    int run = 0;
    for (int x = 0; x < w; ++x) {
      run = rgb[(static_cast<std::size_t>(y) * w + x) * 3] == 1.0f ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  EXPECT_NEAR(longest, b.length_px, 0.5);
  // Nothing leaves [0, 1] and the untouched field keeps its value far from the bar.
  for (float v : rgb) ASSERT_TRUE(v == 0.0f || v == 0.25f || v == 1.0f);
  EXPECT_EQ(rgb[(10 * w + 400) * 3], 0.25f);
}

}  // namespace
}  // namespace pmsim
