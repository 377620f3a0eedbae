// The fine focus in the app by its two input paths that are not the slider: Shift+Up/Down (1 µm a
// press) and Ctrl + mouse wheel over the field (1 µm a notch, + = focusing up), and what must not
// move it: the wheel without Ctrl, and the wheel outside the field.
#include <gtest/gtest.h>

// The GL headers first (as the other UI tests), then GLFW's key codes.
#include "ui/headless_driver.h"

#include <GLFW/glfw3.h>

namespace pmsim::ui {
namespace {

std::unique_ptr<HeadlessDriver> mount_driver() {
  Scene s;
  s.sample.type = SampleType::Grains;
  s.sample.mineral = "garnet";
  s.render.width = s.render.height = 32;
  s.render.spp = 4;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  EXPECT_TRUE(d) << log;
  return d;
}

// Frames until an injected input has been applied and the next frame released it.
void frames(UiDriver& d, int n = 3) {
  for (int i = 0; i < n; ++i) d.frame();
}

TEST(UiFineFocus, ShiftUpDownStepOneMicrometre) {
  auto d = mount_driver();
  ASSERT_TRUE(d);
  frames(*d);
  const double f0 = d->app().scene().focus_um;
  for (int k = 0; k < 3; ++k) {
    d->inject_key(GLFW_KEY_UP, true, false);
    frames(*d, 2);
  }
  // Exact: whole micrometre steps from 0 are exact in binary floating point.
  EXPECT_EQ(d->app().scene().focus_um, f0 + 3.0);
  d->inject_key(GLFW_KEY_DOWN, true, false);
  frames(*d, 2);
  EXPECT_EQ(d->app().scene().focus_um, f0 + 2.0);
}

TEST(UiFineFocus, CtrlWheelOverTheFieldFocusesAndPlainWheelDoesNot) {
  auto d = mount_driver();
  ASSERT_TRUE(d);
  frames(*d);
  const Rect f = d->app().layout().field;
  d->inject_mouse(f.x + 0.5f * f.w, f.y + 0.5f * f.h, false);
  frames(*d);
  const double f0 = d->app().scene().focus_um;
  d->inject_wheel(2.0f, true);  // two notches up
  frames(*d);
  EXPECT_EQ(d->app().scene().focus_um, f0 + 2.0);
  d->inject_wheel(-5.0f, true);
  frames(*d);
  EXPECT_EQ(d->app().scene().focus_um, f0 - 3.0);
  // Without Ctrl the wheel is not the focus (it stays with ImGui: scrolling, zoom elsewhere).
  d->inject_wheel(4.0f, false);
  frames(*d);
  EXPECT_EQ(d->app().scene().focus_um, f0 - 3.0);
  // Outside the field (over the control panel) Ctrl + wheel does not focus either.
  const Rect c = d->app().layout().controls;
  d->inject_mouse(c.x + 0.5f * c.w, c.y + 0.9f * c.h, false);
  frames(*d);
  d->inject_wheel(1.0f, true);
  frames(*d);
  EXPECT_EQ(d->app().scene().focus_um, f0 - 3.0);
}

}  // namespace
}  // namespace pmsim::ui
