// Measures (and prints) the UI frame rate at 1280×800 with software OpenGL while the renderer
// works on the other cores: once while a 512×512 thin section refines (the stage is stepped every
// 15 frames so that refinement never stops), once while the stage is dragged (a restart every
// frame), and the frames from a change to the first image of it (section and conoscopic figure).
// Timing is reported, never asserted: on a loaded 2-core machine any figure can happen. What is
// asserted is that every frame was drawn and that the field keeps updating while frames are drawn
// (waits are bounded by generous deadlines, not frame counts).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "ui/headless_driver.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

// Runs frames until the uploads counter moves past `uploads`, giving the workers the cores between
// frames; false only after a deadline far beyond any loaded machine's time for one image.
bool frames_until_new_image(UiDriver& d, std::uint64_t uploads, double deadline_s = 300) {
  const auto start = std::chrono::steady_clock::now();
  while (d.app().counters().uploads == uploads) {
    d.frame();
    d.app().wait_rendered(0.01);
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > deadline_s)
      return false;
  }
  return true;
}

struct FirstImage {
  double mean_frames = 0, mean_ms = 0, max_ms = 0;
  std::uint64_t max_frames = 0, changes = 0;
};

// Steps the stage `changes` times, each time running frames until the changed scene's first
// image is on screen; the App counts the frames. Frames are paced at 60 Hz as the windowed app's
// are (glfwSwapInterval(1) waits for the display): a headless loop drawing frames back to back
// would count frames of ~10 ms and keep a core busy that a real UI leaves to the renderer.
FirstImage measure_first_image(UiDriver& d, int changes) {
  using namespace std::chrono;
  const AppCounters c0 = d.app().counters();
  double sum_ms = 0, max_ms = 0;
  const auto period = duration_cast<steady_clock::duration>(duration<double>(1.0 / 60.0));
  for (int i = 0; i < changes; ++i) {
    // The change comes with a frame's input, then that frame is drawn.
    EXPECT_TRUE(d.app().set("stage_deg=" + std::to_string(5 * (i + 1))));
    const auto start = steady_clock::now();
    auto next = start;
    for (;;) {
      d.frame();
      if (d.app().image_current() || duration<double>(steady_clock::now() - start).count() > 300) break;
      next += period;
      std::this_thread::sleep_until(next);
    }
    EXPECT_TRUE(d.app().image_current());
    // From the change to the end of the frame that shows its first image.
    const double ms = duration<double, std::milli>(steady_clock::now() - start).count();
    sum_ms += ms;
    max_ms = std::max(max_ms, ms);
  }
  const AppCounters& c = d.app().counters();
  FirstImage f;
  f.mean_ms = sum_ms / std::max(1, changes);
  f.max_ms = max_ms;
  f.changes = c.first_images - c0.first_images;
  f.mean_frames = static_cast<double>(c.first_image_frames - c0.first_image_frames) /
                  std::max<std::uint64_t>(1, f.changes);
  f.max_frames = c.first_image_frames_max;
  return f;
}

TEST(UiFrameRate, ReportsFramesPerSecondWhileRendering) {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.render.width = s.render.height = 512;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  for (int i = 0; i < 10; ++i) d->frame();  // warm-up
  ASSERT_TRUE(frames_until_new_image(*d, 0)) << "no image of the section at all";
  const size_t base = d->frame_times().ms.size();
  const auto uploads0 = d->app().counters().uploads;
  for (int i = 0; i < 60; ++i) {
    if (i % 15 == 0) {
      ASSERT_TRUE(d->app().set("stage_deg=" + std::to_string(7 * (i / 15 + 1))));
    }
    ASSERT_TRUE(d->frame());
  }
  FrameTimes refining;
  refining.ms.assign(d->frame_times().ms.begin() + base, d->frame_times().ms.end());
  const auto uploads1 = d->app().counters().uploads;
  // The field refines while the UI runs: a new image comes while frames go on being drawn.
  EXPECT_TRUE(frames_until_new_image(*d, uploads0)) << "the field did not refine while the UI ran";

  // Dragging: the arc command restarts the renderer on every frame of the drag.
  const size_t base2 = d->frame_times().ms.size();
  const ScriptResult r = run_script(*d, parse_script("turn-stage 90 60\n", "fps"), "fps");
  ASSERT_TRUE(r.ok) << r.error;
  FrameTimes dragging;
  dragging.ms.assign(d->frame_times().ms.begin() + base2, d->frame_times().ms.end());
  EXPECT_EQ(refining.ms.size(), 60u);
  EXPECT_GE(dragging.ms.size(), 60u);
  // After the drag the renderer is on the final stage angle, and the field shows it.
  EXPECT_TRUE(frames_until_new_image(*d, d->app().counters().uploads) || d->app().image_current());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  while (!d->app().image_current() && std::chrono::steady_clock::now() < deadline) {
    d->frame();
    d->app().wait_rendered(0.01);
  }
  EXPECT_TRUE(d->app().image_current());

  const FirstImage section = measure_first_image(*d, 8);
  // A conoscopic figure (the calcite plate cut perpendicular to c of the presets) at 512².
  ASSERT_TRUE(d->app().load_scene(std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/calcite_cono.json"))
      << d->app().error();
  ASSERT_TRUE(frames_until_new_image(*d, d->app().counters().uploads));
  const FirstImage figure = measure_first_image(*d, 8);
  EXPECT_EQ(section.changes, 8u);
  EXPECT_EQ(figure.changes, 8u);

  std::printf(
      "[fps] 1280x800 %s: refining 512^2 section %.1f fps (p95 %.1f ms, %llu new images "
      "in %zu frames), dragging the stage %.1f fps (p95 %.1f ms); first image of a change "
      "on screen (frames paced at 60 Hz) after %.1f frames, %.1f ms on average (section 512^2; at "
      "most %.1f ms), %.1f frames, %.1f ms (conoscopic figure 512^2; at most %.1f ms), %llu "
      "frames at most\n",
      d->gl_name(), refining.fps(), refining.percentile_ms(0.95),
      static_cast<unsigned long long>(uploads1 - uploads0), refining.ms.size(), dragging.fps(),
      dragging.percentile_ms(0.95), section.mean_frames, section.mean_ms, section.max_ms, figure.mean_frames,
      figure.mean_ms, figure.max_ms,
      static_cast<unsigned long long>(std::max(section.max_frames, figure.max_frames)));
}

}  // namespace
}  // namespace pmsim::ui
