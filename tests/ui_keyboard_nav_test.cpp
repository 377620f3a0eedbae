// The app from the keyboard alone (issue 23): F6 hands the arrows, Space and Enter to the panels'
// widgets (ImGui keyboard navigation), so every control can be reached and worked without a mouse;
// F6 again gives the arrows back to the stage and the polarizer.
#include "ui/headless_driver.h"

#include <gtest/gtest.h>

#include <GLFW/glfw3.h>

namespace pmsim::ui {
namespace {

void press(UiDriver& d, int key, int times = 1) {
  for (int i = 0; i < times; ++i) {
    d.inject_key(key, false, false);
    d.frame();
    d.frame();
  }
}

// Pixels of ImGui's navigation highlight (ImGuiCol_NavHighlight, (0.26, 0.59, 0.98) in the dark
// style: sRGB bytes (66, 150, 250) within 12) in the controls panel.
int highlight_pixels(const WindowPixels& px, const Layout& l) {
  int n = 0;
  for (int y = 0; y < px.height; ++y)
    for (int x = 0; x < int(l.controls.w); ++x) {
      const std::uint8_t* p = &px.rgb[(std::size_t(y) * px.width + x) * 3];
      n += std::abs(p[0] - 66) < 12 && std::abs(p[1] - 150) < 12 && std::abs(p[2] - 250) < 12;
    }
  return n;
}

}  // namespace

TEST(UiKeyboard, F6NavigatesThePanelsAndGivesTheArrowsBack) {
  Scene s;
  s.render.width = s.render.height = 32;
  s.optics.relief = false;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  d->frame();
  const int before = highlight_pixels(d->read_pixels(), d->app().layout());
  press(*d, GLFW_KEY_F6);
  // Up to the top of the Microscope tab, down to the View row, right to "Conoscopic", Space.
  press(*d, GLFW_KEY_UP, 20);
  press(*d, GLFW_KEY_DOWN);
  press(*d, GLFW_KEY_RIGHT);
  const int during = highlight_pixels(d->read_pixels(), d->app().layout());
  press(*d, GLFW_KEY_SPACE);
  EXPECT_EQ(d->app().scene().mode, ViewMode::Cono) << "Space on the highlighted radio button";
  EXPECT_EQ(d->app().scene().stage_deg, 0.0) << "while navigating, the arrows do not turn the stage";
  EXPECT_EQ(d->app().scene().polarizer_deg, 0.0);
  std::printf("navigation highlight: %d px before F6, %d px on a widget\n", before, during);
  EXPECT_GT(during, before + 40) << "the highlighted widget is framed";
  press(*d, GLFW_KEY_F6);
  press(*d, GLFW_KEY_LEFT);
  EXPECT_EQ(d->app().scene().stage_deg, 1.0) << "F6 again: Left turns the stage 1° counter-clockwise";
}

}  // namespace pmsim::ui
