// The colours of a near match (issue 12): a fragment of n_D = the liquid's n_D but of lower
// dispersion. Blue light then meets a liquid of higher index than the fragment, red light one of
// lower index, so the two Becke lines go opposite ways: focused up, the blue one moves out into
// the liquid and the red one into the fragment (bluish outside, orange inside).
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/specimen_fixture.h"

using namespace specimen_test;

namespace {

OneFragment near_match() {
  OneFragment f;
  f.n_fragment = 1.60;         // no dispersion: the mineral's is far below the liquid's
  f.n_liquid = 1.60;
  f.liquid_dispersion = 0.03;  // n_F − n_C of a 1.60 liquid of the series is ≈ 0.026
  return f;
}

double brightest_band_side(const pmsim::SpecimenScene& s, double wavelength_nm) {
  auto o = mono_view(20.0, 32);
  o.single_wavelength_nm = wavelength_nm;
  const auto img = pmsim::render_plane_light(s, o);
  const auto d = signed_distance(s, o);
  double peak = 0.0, where = 0.0;
  for (double a = -14; a < 14; a += 2) {
    const double m = band_mean(img, d, a, a + 2);
    if (m > peak) peak = m, where = a + 1;
  }
  std::printf("λ %.0f nm: brightest band %.3f at %+.0f µm\n", wavelength_nm, peak, where);
  return where;
}

}  // namespace

TEST(SpecimenDispersion, BlueAndRedBeckeLinesGoOppositeWaysAtANearMatch) {
  const auto s = make_specimen(near_match());
  // Liquid at 450 nm: 1.60 + 0.03·(1/450² − 1/589²)/(1/486² − 1/656²) ≈ 1.6100 > 1.60;
  // at 680 nm ≈ 1.5949 < 1.60: an index difference of ±0.005 to 0.01 either way.
  EXPECT_LT(brightest_band_side(*s, 450.0), 0.0) << "blue: liquid higher, fringe goes out";
  EXPECT_GT(brightest_band_side(*s, 680.0), 0.0) << "red: fragment higher, fringe goes in";
}

// In white light the same shows as colour: the band just outside the outline is bluer (larger
// B/R in linear sRGB) than the band just inside. Bands of 6 µm at focus +20 µm, 64 samples;
// the ratio differs by far more than its noise (≈ 0.01 over ~2000 pixels).
TEST(SpecimenDispersion, NearMatchOutlineIsBluishOutsideAndOrangeInside) {
  const auto s = make_specimen(near_match());
  auto o = mono_view(20.0, 64);
  o.single_wavelength_nm = 0.0;
  const auto img = pmsim::render_plane_light(*s, o);
  const auto d = signed_distance(*s, o);
  auto blue_over_red = [&](double lo, double hi) {
    double b = 0.0, r = 0.0;
    for (std::size_t i = 0; i < d.size(); ++i)
      if (d[i] >= lo && d[i] < hi) r += img.rgb[3 * i], b += img.rgb[3 * i + 2];
    return b / r;
  };
  const double outside = blue_over_red(-6, 0), inside = blue_over_red(0, 6), far = blue_over_red(-40, -30);
  std::printf("B/R outside %.3f, inside %.3f, empty field %.3f\n", outside, inside, far);
  EXPECT_GT(outside, inside + 0.05);
  EXPECT_NEAR(far, 1.0, 0.02) << "the empty field is white (D65 → linear sRGB ≈ (1, 1, 1))";
}
