// The windowed path (GLFW + OpenGL 3.3 core + ImGui's GLFW/OpenGL3 backends) for a few frames on
// the display CI gives it (Xvfb, Mesa llvmpipe), with a window screenshot read back from it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "core/io/image_file.h"
#include "ui/script.h"
#include "ui/window_driver.h"

namespace pmsim::ui {
namespace {

TEST(UiWindow, OpensDrawsFramesAndItsScreenshotShowsTheWhiteField) {
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
    GTEST_SKIP() << "no display (CI runs this under xvfb-run)";
  Scene s;
  s.render.width = s.render.height = 64;
  s.sample_in = false;
  s.analyzer_in = false;
  std::string log;
  auto d = WindowDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(d->frame());
  ASSERT_TRUE(settle(*d, 60));
  EXPECT_GE(d->app().counters().frames, 6u);

  const std::string path = std::string(PMSIM_BINARY_DIR) + "/ui_window_test_shot.png";
  std::filesystem::remove(path);
  d->app().request_window_screenshot(path);
  ASSERT_TRUE(d->frame());
  ASSERT_TRUE(d->app().error().empty()) << d->app().error();
  const LoadedImage img = read_image(path);
  ASSERT_GT(img.width, 0);
  const Layout& l = d->app().layout();
  const double scale = static_cast<double>(img.width) / d->width();  // HiDPI framebuffers
  const int x = static_cast<int>((l.field.cx() + 30) * scale);
  const int y = static_cast<int>((l.field.cy() + 30) * scale);
  const float* p = &img.pixels[(static_cast<size_t>(y) * img.width + x) * img.channels];
  // Analyzer out, empty stage: white (Y = 1); 0.96 of full scale allows texture filtering.
  EXPECT_GT(p[0], 0.96f);
  EXPECT_GT(p[1], 0.96f);
  EXPECT_GT(p[2], 0.96f);
  // The scene travels in the screenshot's metadata.
  EXPECT_TRUE(img.metadata.contains("pmsim:scene"));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace pmsim::ui
