// The compensator test by brightness (core/render/brightness_test.h) against the closed form of
// the Michel-Lévy intensity: for monochromatic light I = sin²(πΓ/λ) at 45° between crossed polars
// (Nesse 2012 §7), so in white light the luminance follows the same curve smeared over the
// spectrum. A first-order grey (Γ = 100 nm) with the mica λ/4 plate: addition gives 247 nm
// (sin² ≈ 0.88 at 550 nm), subtraction 47 nm (0.07): brighter on addition. With the gypsum plate
// the first-order grey goes to second-order blue (650 nm) or first-order yellow (450 nm), whose
// white-light luminances differ by only 0.025 (measured) — a change of hue more than of brightness,
// which is why the mica plate is the test to read by brightness; a first-order white (200 nm)
// goes to 750 or 350 nm: 0.74 against 0.82, brighter on subtraction.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/brightness_test.h"
#include "core/render/michel_levy_chart.h"

using namespace pmsim;

TEST(BrightnessTest, MicaBrightensFirstOrderGreyOnAddition) {
  const BrightnessTest t = brightness_test(100.0, Compensator::Mica);
  EXPECT_NEAR(t.accessory_nm, 147.0, 10.0);  // the λ/4 of sodium light the plates are sold as
  EXPECT_EQ(t.reading, "brighter on addition");
  EXPECT_GT(t.y_addition, t.y_alone);
  EXPECT_LT(t.y_subtraction, t.y_alone);
}

TEST(BrightnessTest, GypsumReadsByBrightnessOnlyAboveTheGreys) {
  const BrightnessTest grey = brightness_test(100.0, Compensator::Gypsum), white = brightness_test(200.0, Compensator::Gypsum);
  EXPECT_NEAR(grey.accessory_nm, 550.0, 1.0);
  EXPECT_EQ(grey.reading, "undecided");
  EXPECT_EQ(white.reading, "brighter on subtraction");
  // The values are the chart's luminances at Γ ± 550 nm.
  EXPECT_DOUBLE_EQ(white.y_addition, michel_levy_xyz(200.0 + white.accessory_nm, Illuminant::D65).y);
  EXPECT_DOUBLE_EQ(white.y_subtraction, michel_levy_xyz(white.accessory_nm - 200.0, Illuminant::D65).y);
}

// Where addition and subtraction give the same luminance the test says so: with gypsum,
// Γ = 550 nm gives 1100 and 0 nm — 0 is black, 1100 bright — but Γ near 275 nm gives 825 and
// 275 nm, both bright; somewhere between the reading must change through "undecided".
TEST(BrightnessTest, SaysWhenBrightnessCannotTell) {
  bool undecided = false, addition = false, subtraction = false;
  for (double g = 0; g <= 1100; g += 5) {
    const std::string r = brightness_test(g, Compensator::Gypsum).reading;
    undecided |= r == "undecided", addition |= r == "brighter on addition", subtraction |= r == "brighter on subtraction";
  }
  EXPECT_TRUE(undecided && addition && subtraction);
  EXPECT_THROW(brightness_test(100.0, Compensator::QuartzWedge), std::invalid_argument);
}
