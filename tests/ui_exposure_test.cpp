// render.exposure_ev in the app: the field is encoded as image × 2^ev, so one stop down turns the
// empty field's white (Y = 1) into sRGB's encoding of 0.5 (188 of 255), without restarting the
// render (the exposure is how the image is shown, not what it is).
#include "ui/headless_driver.h"

#include <gtest/gtest.h>

#include "ui/script.h"

namespace pmsim::ui {
namespace {

// Mean of R, G, B of the window pixel at a point of the field away from the crosshair.
double field_grey(const WindowPixels& px, const Layout& l) {
  const int x = int(l.field.cx() + 0.3f * l.field.w / 2), y = int(l.field.y + 0.5f * l.field.h + 0.2f * l.field.h / 2);
  const std::uint8_t* p = &px.rgb[(std::size_t(y) * px.width + x) * 3];
  return (p[0] + p[1] + p[2]) / 3.0;
}

TEST(UiExposure, OneStopDownHalvesTheLinearFieldWithoutARestart) {
  Scene s;
  s.render.width = s.render.height = 64;
  s.sample_in = false;
  s.analyzer_in = false;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  ASSERT_TRUE(settle(*d, 120));
  const Layout l = d->app().layout();
  const double white = field_grey(d->read_pixels(), l);
  const std::uint64_t generation = d->app().image().generation;
  ASSERT_TRUE(d->app().set("render.exposure_ev=-1"));
  for (int i = 0; i < 3; ++i) d->frame();
  const double half = field_grey(d->read_pixels(), l);
  std::printf("empty field: %.1f at ev 0, %.1f at ev -1 (of 255)\n", white, half);
  // Y = 1 white encodes as 255 (the screenshot test's convention allows 245 for filtering).
  EXPECT_GT(white, 245.0);
  // sRGB encoding of 0.5: 1.055·0.5^(1/2.4) − 0.055 = 0.7354 → 187.5; ±3 levels for the field's
  // D65 white being (1, 1, 1) only to ~1 % in linear sRGB and for texture filtering.
  EXPECT_NEAR(half, 187.5, 3.0);
  EXPECT_EQ(d->app().image().generation, generation) << "an exposure change must not restart the render";
  EXPECT_EQ(d->app().scene().render.exposure_ev, -1.0);
}

}  // namespace
}  // namespace pmsim::ui
