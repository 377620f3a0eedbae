// Measures (and prints) the UI frame rate at 1280×800 with software OpenGL while the renderer
// works on the other cores: once while a 512×512 thin section refines (the stage is stepped every
// 15 frames so that refinement never stops; one such image converges in about 0.2 s), once while
// the stage is dragged (a restart every frame). Timing is reported, never asserted; what is asserted
// is that every frame was drawn and the field kept updating.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "ui/headless_driver.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

TEST(UiFrameRate, ReportsFramesPerSecondWhileRendering) {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "granite";
  s.render.width = s.render.height = 512;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  for (int i = 0; i < 10; ++i) d->frame();  // warm-up
  const size_t base = d->frame_times().ms.size();
  const auto uploads0 = d->app().counters().uploads;
  // Also counted: frames from a change to the first image of the changed scene on screen.
  int changes = 0, latency_frames = 0, max_latency = 0, since_change = -1;
  for (int i = 0; i < 60; ++i) {
    if (i % 15 == 0) {
      ASSERT_TRUE(d->app().set("stage_deg=" + std::to_string(7 * (i / 15 + 1))));
      since_change = 0;
      ++changes;
    }
    ASSERT_TRUE(d->frame());
    if (since_change >= 0) {
      ++since_change;
      if (d->app().image_current()) {
        latency_frames += since_change;
        max_latency = std::max(max_latency, since_change);
        since_change = -1;
      }
    }
  }
  FrameTimes refining;
  refining.ms.assign(d->frame_times().ms.begin() + base, d->frame_times().ms.end());
  const auto uploads1 = d->app().counters().uploads;

  // Dragging: the arc command restarts the renderer on every frame of the drag.
  const size_t base2 = d->frame_times().ms.size();
  const ScriptResult r = run_script(*d, parse_script("turn-stage 90 60\n", "fps"), "fps");
  ASSERT_TRUE(r.ok) << r.error;
  FrameTimes dragging;
  dragging.ms.assign(d->frame_times().ms.begin() + base2, d->frame_times().ms.end());

  std::printf("[fps] 1280x800 %s: refining %.1f fps (p95 %.1f ms, %llu new images in %zu "
              "frames), dragging the stage %.1f fps (p95 %.1f ms); first image of a change "
              "after %.1f frames on average, %d at most\n",
              d->gl_name(), refining.fps(), refining.percentile_ms(0.95),
              static_cast<unsigned long long>(uploads1 - uploads0), refining.ms.size(),
              dragging.fps(), dragging.percentile_ms(0.95),
              static_cast<double>(latency_frames) / std::max(1, changes), max_latency);
  EXPECT_EQ(refining.ms.size(), 60u);
  EXPECT_GE(dragging.ms.size(), 60u);
  EXPECT_GT(uploads1, uploads0) << "the field did not refine while the UI ran";
  // After the drag the renderer is on the final stage angle, and the field shows it.
  const auto uploads2 = d->app().counters().uploads;
  for (int i = 0; i < 600 && d->app().counters().uploads == uploads2; ++i) {
    d->frame();
    d->app().wait_rendered(0.01);
  }
  EXPECT_GT(d->app().counters().uploads, uploads2);
}

}  // namespace
}  // namespace pmsim::ui
