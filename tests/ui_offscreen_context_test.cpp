// Both off-screen GL paths of `pmsim --headless`: EGL on Mesa's surfaceless platform and the
// OSMesa fallback (with ImGui's OpenGL3 backend compiled against OSMesa's entry points) draw the
// same window.
#include <gtest/gtest.h>

#include <cstdlib>

#include "ui/headless_driver.h"
#include "ui/offscreen_context.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

class ForcedGl {
 public:
  explicit ForcedGl(const char* api) { setenv("PMSIM_GL", api, 1); }
  ~ForcedGl() { unsetenv("PMSIM_GL"); }
};

void expect_window_drawn(OffscreenApi api, const char* name) {
  ForcedGl force(name);
  Scene s;
  s.render.width = s.render.height = 64;
  s.sample_in = false;
  s.analyzer_in = false;  // white field: easy to tell from the UI's dark panels
  std::string log;
  auto d = HeadlessDriver::create(s, 640, 400, log);
  ASSERT_TRUE(d) << log;
  EXPECT_STREQ(d->gl_name(), api == OffscreenApi::OSMesa ? "OSMesa" : "EGL surfaceless");
  ASSERT_TRUE(settle(*d, 60));
  const WindowPixels px = d->read_pixels();
  ASSERT_EQ(px.width, 640);
  ASSERT_EQ(px.height, 400);
  const Layout& l = d->app().layout();
  // Field centre (beside the crosshair) white, the controls panel dark.
  const std::uint8_t* c =
      &px.rgb[(static_cast<size_t>(l.field.cy() + 20) * px.width + static_cast<int>(l.field.cx() + 20)) * 3];
  EXPECT_GT(c[0], 245);
  EXPECT_GT(c[2], 245);
  const std::uint8_t* panel = &px.rgb[(static_cast<size_t>(px.height - 5) * px.width + 5) * 3];
  EXPECT_LT(panel[0], 60);
}

TEST(UiOffscreen, EglSurfacelessDrawsTheWindow) { expect_window_drawn(OffscreenApi::EglSurfaceless, "egl"); }

TEST(UiOffscreen, OSMesaFallbackDrawsTheWindow) { expect_window_drawn(OffscreenApi::OSMesa, "osmesa"); }

}  // namespace
}  // namespace pmsim::ui
