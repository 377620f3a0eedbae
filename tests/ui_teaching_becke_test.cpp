// The teaching panel's Becke-line sentence in the app: for a grain mount and for a thin section
// (orthoscopic, plane light) the panel shows at the probe what core's probes say for the same
// scene and point, and it follows a change of the mounting medium's index.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "core/specimen/becke_probe.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/section_becke_probe.h"
#include "ui/headless_driver.h"

namespace pmsim::ui {
namespace {

// Frames until the panel's Becke sentence equals `want` (the probe runs off the UI thread).
std::string wait_for_text(UiDriver& d, const std::string& want, double timeout_s = 10.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::string text;
  while (std::chrono::steady_clock::now() < end) {
    d.frame();
    text = d.app().becke_text();
    if (text == want) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return text;
}

// Untouched by the mouse the probe stays at the field's centre, image fractions (0.5, 0.5).
TEST(UiTeachingBecke, ThinSectionShowsTheBoundaryAndFollowsTheMountingMedium) {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.analyzer_in = false;
  s.objective.magnification = 40.0;
  s.render.width = s.render.height = 32;
  s.render.spp = 4;
  // A stage position whose centre lies near the mounting medium (a crack or the section's
  // edge), found with core's probe: there the sentence must change with the medium's index.
  bool near_medium = false;
  for (int k = 0; k < 400 && !near_medium; ++k) {
    s.stage = {-1.0 + 0.05 * (k % 40), -0.5 + 0.1 * (k / 40)};
    const SectionBeckeProbe p = probe_section_becke_line(s, 0.5, 0.5);
    near_medium = p.found && p.here.is_medium() != p.there.is_medium();
  }
  ASSERT_TRUE(near_medium) << "no crack near any probed stage position of the granite";
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  std::string previous;
  for (const double nd : {1.45, 1.75}) {
    ASSERT_TRUE(d->app().set("sample.medium_index=" + std::to_string(nd)));
    const SectionBeckeProbe p = probe_section_becke_line(d->app().scene(), 0.5, 0.5);
    const std::string want = describe_section_becke_line(p);
    EXPECT_EQ(wait_for_text(*d, want), want) << "medium " << nd;
    // The sentence names the mineral under the probe and, when a boundary is near, the other side.
    EXPECT_NE(want.find(section_becke_side_name(p.here)), std::string::npos) << want;
    if (p.found) {
      EXPECT_NE(want.find(section_becke_side_name(p.there)), std::string::npos) << want;
    }
    std::printf("medium %.2f: %s\n", nd, want.c_str());
    // Granite's minerals lie between 1.45 and 1.75: the line changes side, and so the sentence.
    EXPECT_NE(want, previous);
    previous = want;
  }
}

TEST(UiTeachingBecke, GrainMountShowsTheCoreProbesSentence) {
  Scene s;
  s.sample.type = SampleType::Grains;
  s.sample.mineral = "almandine";
  s.sample.medium_index = 1.54;
  s.render.width = s.render.height = 32;
  s.render.spp = 4;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  const auto mount = grain_mount_specimen(d->app().scene());
  const std::string want = describe_becke_line(probe_becke_line(*mount, d->app().scene(), 0.5, 0.5));
  EXPECT_EQ(wait_for_text(*d, want), want);
}

}  // namespace
}  // namespace pmsim::ui
