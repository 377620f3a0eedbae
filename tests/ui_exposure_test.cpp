// render.exposure_ev in the app: the field is encoded as image × 2^ev, so one stop down turns the
// empty field's white (Y = 1) into sRGB's encoding of 0.5 (188 of 255), without restarting the
// render (the exposure is how the image is shown, not what it is).
#include "ui/headless_driver.h"

#include <gtest/gtest.h>

#include <cmath>

#include <glm/glm.hpp>

#include "core/spectrum/colour_vision.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

// Mean of R, G, B of the window pixel at a point of the field away from the crosshair.
const std::uint8_t* field_pixel(const WindowPixels& px, const Layout& l) {
  const int x = int(l.field.cx() + 0.3f * l.field.w / 2), y = int(l.field.y + 0.5f * l.field.h + 0.2f * l.field.h / 2);
  return &px.rgb[(std::size_t(y) * px.width + x) * 3];
}
double field_grey(const WindowPixels& px, const Layout& l) {
  const std::uint8_t* p = field_pixel(px, l);
  return (p[0] + p[1] + p[2]) / 3.0;
}
double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

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

// render.vision in the app: the field is shown through Machado's Φ (core/spectrum/colour_vision.h)
// at once, without a restart. A first-order yellow quartz plate one stop down (no channel clips):
// each channel of the shown pixel is Φ of the normal one within 3 % + 0.004 in linear (two 8-bit
// quantizations and texture filtering).
TEST(UiExposure, ColourVisionReshowsTheFieldThroughItsMatrixWithoutARestart) {
  Scene s;
  s.render.width = s.render.height = 64;
  s.render.exposure_ev = -1.0;
  s.sample.type = SampleType::Plate;
  s.sample.mineral = "quartz";
  s.sample.thickness_um = 40.0;
  s.sample.optic_axis = {0.70710678, 0.70710678, 0.0};
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  ASSERT_TRUE(settle(*d, 120));
  const Layout l = d->app().layout();
  const WindowPixels before = d->read_pixels();
  const std::uint8_t* p = field_pixel(before, l);
  const glm::dvec3 normal(srgb_to_linear(p[0] / 255.0), srgb_to_linear(p[1] / 255.0), srgb_to_linear(p[2] / 255.0));
  const std::uint64_t generation = d->app().image().generation;
  ASSERT_TRUE(d->app().set("render.vision=tritanopia"));
  for (int i = 0; i < 3; ++i) d->frame();
  const WindowPixels after = d->read_pixels();
  const std::uint8_t* q = field_pixel(after, l);
  const glm::dvec3 want = glm::clamp(colour_vision_matrix(ColourVision::Tritanopia) * normal, 0.0, 1.0);
  ASSERT_GT(std::abs(normal.x - normal.z), 0.1) << "the plate must be coloured";
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(srgb_to_linear(q[c] / 255.0), want[c], 0.03 * want[c] + 0.004) << "channel " << c;
  EXPECT_EQ(d->app().image().generation, generation) << "a vision change must not restart the render";
}

}  // namespace
}  // namespace pmsim::ui
