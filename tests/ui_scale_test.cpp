// ui.scale (ui/ui_scale.h): the interface grows with the setting — text, widgets and side panels —
// for a projector or a high-density monitor; "auto" follows the monitor's content scale; bad values
// are refused without changing anything.
#include "ui/headless_driver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "ui/script.h"

namespace pmsim::ui {
namespace {

// Height in pixels of the bright text in the controls panel's title bar ("Microscope", top left):
// the rows between the first and the last with a near-white pixel in it.
int title_text_height(const WindowPixels& px, const Layout& l, float scale) {
  const int x1 = int(std::min(l.controls.w, 120.0f * scale)), y1 = int(std::min(float(px.height), 26.0f * scale));
  int top = -1, bottom = -1;
  for (int y = 0; y < y1; ++y)
    for (int x = 0; x < x1; ++x) {
      const std::uint8_t* p = &px.rgb[(std::size_t(y) * px.width + x) * 3];
      if (p[0] > 200 && p[1] > 200 && p[2] > 200) {
        if (top < 0) top = y;
        bottom = y;
        break;
      }
    }
  return top < 0 ? 0 : bottom - top + 1;
}

}  // namespace

// A 1280×800 off-screen app over an empty 32² stage: the panels, not the specimen, are measured.
class UiScale : public ::testing::Test {
 protected:
  void SetUp() override {
    Scene s;
    s.render.width = s.render.height = 32;
    s.sample_in = false;
    d = HeadlessDriver::create(s, 1280, 800, log);
    ASSERT_TRUE(d) << log;
  }
  std::string log;
  std::unique_ptr<HeadlessDriver> d;
};

// Scale 2 doubles the title's glyphs (14 px font rasterised once and scaled: 2× to within a pixel
// of antialiasing each side) and widens the side panels with them (a quarter of 1280 = 320 px at
// scale 1; at 2 the 520 px they need, within the 40 % cap of 512).
TEST_F(UiScale, TwiceTheScaleTwiceTheText) {
  for (int i = 0; i < 2; ++i) d->frame();
  EXPECT_FLOAT_EQ(d->app().ui_scale(), 1.0f) << "off-screen the content scale is 1";
  const int h1 = title_text_height(d->read_pixels(), d->app().layout(), 1.0f);
  const float w1 = d->app().layout().controls.w;
  ASSERT_TRUE(d->app().set("ui.scale=2"));
  for (int i = 0; i < 2; ++i) d->frame();
  const int h2 = title_text_height(d->read_pixels(), d->app().layout(), 2.0f);
  const float w2 = d->app().layout().controls.w;
  std::printf("title text %d px at 1, %d px at 2; panel %.0f and %.0f px\n", h1, h2, w1, w2);
  ASSERT_GT(h1, 5);
  EXPECT_NEAR(double(h2), 2.0 * h1, 2.0);
  EXPECT_FLOAT_EQ(w1, 320.0f);
  EXPECT_FLOAT_EQ(w2, 512.0f);
  EXPECT_GT(d->app().layout().field.w, 64.0f) << "the field keeps its place";
}

TEST_F(UiScale, AutoFollowsTheContentScaleAndBadValuesAreRefused) {
  d->app().set_content_scale(1.5f);
  EXPECT_FLOAT_EQ(d->app().ui_scale(), 1.5f);
  ASSERT_TRUE(d->app().set("ui.scale=1.25"));
  EXPECT_FLOAT_EQ(d->app().ui_scale(), 1.25f) << "a set scale overrides the monitor's";
  const auto rejected = d->app().counters().rejected;
  EXPECT_FALSE(d->app().set("ui.scale=4"));
  EXPECT_FALSE(d->app().set("ui.scale=big"));
  EXPECT_FALSE(d->app().set("ui.colour=red"));
  EXPECT_EQ(d->app().counters().rejected, rejected + 3);
  EXPECT_FLOAT_EQ(d->app().ui_scale(), 1.25f) << "a refused value changes nothing";
  ASSERT_TRUE(d->app().set("ui.scale=auto"));
  EXPECT_FLOAT_EQ(d->app().ui_scale(), 1.5f);
  EXPECT_EQ(d->app().scene().render.width, 32) << "ui keys do not touch the scene";
}

}  // namespace pmsim::ui
