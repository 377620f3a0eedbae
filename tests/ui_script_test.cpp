// Scripts replay user actions through the same paths as the mouse and the keyboard: a drag on the
// field turns the stage, shortcut keys flip the instrument, bad input raises the banner and keeps
// the last good scene, exports carry the scene in their metadata.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/io/image_file.h"
#include "core/base/input_error.h"
#include "core/io/scene_file.h"
#include "ui/headless_driver.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

std::unique_ptr<HeadlessDriver> driver() {
  Scene s;
  s.render.width = s.render.height = 48;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  EXPECT_TRUE(d) << log;
  return d;
}

ScriptResult run(UiDriver& d, const std::string& text) {
  return run_script(d, parse_script(text, "test.pmsim"), "test.pmsim");
}

std::string out_path(const std::string& name) {
  return std::string(PMSIM_BINARY_DIR) + "/ui_script_test_" + name;
}

TEST(UiScript, ParseErrorsNameTheFileTheLineAndTheText) {
  try {
    parse_script("wait 2\nfrobnicate 3\n", "tour.pmsim");
    FAIL() << "unknown verb accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, "tour.pmsim");
    EXPECT_EQ(e.key, "line 2");
    EXPECT_EQ(e.value, "frobnicate");
  }
  EXPECT_THROW(parse_script("key hyper+Q\n", "f"), InputError);
  EXPECT_THROW(parse_script("drag 1 2 3\n", "f"), InputError);
  EXPECT_THROW(parse_script("move 1 x\n", "f"), InputError);
  EXPECT_THROW(parse_script("set stage_deg\n", "f"), InputError);
  EXPECT_EQ(parse_script("# only a comment\n\n  wait 1  # trailing\n", "f").size(), 1u);
}

TEST(UiScript, DraggingAroundTheFieldCentreTurnsTheStageByTheSweptAngle) {
  auto d = driver();
  ASSERT_TRUE(d);
  const ScriptResult r = run(*d, "turn-stage 30\n");
  ASSERT_TRUE(r.ok) << r.error;
  // ImGui floors mouse positions to whole pixels, as a real mouse reports them; on the arc at
  // 0.35 of the radius (~106 px) one pixel is 0.54°, so the swept angle is good to 0.6°.
  EXPECT_NEAR(d->app().scene().stage_deg, 30.0, 0.6);
  ASSERT_TRUE(run(*d, "turn-stage -45 20\n").ok);
  EXPECT_NEAR(d->app().scene().stage_deg, 345.0, 1.2);  // wrapped into [0, 360); two drags
  // A straight drag that does not pass round the centre: from east to north of it is +90°.
  const Layout& l = d->app().layout();
  const float cx = l.field.cx(), cy = l.field.cy(), r0 = l.field_radius() * 0.5f;
  const std::string drag = "drag " + std::to_string(cx + r0) + " " + std::to_string(cy) + " " +
                           std::to_string(cx) + " " + std::to_string(cy - r0) + " 20\n";
  ASSERT_TRUE(run(*d, drag).ok);
  EXPECT_NEAR(d->app().scene().stage_deg, 75.0, 1.8);  // three drags, 0.6° each
}

TEST(UiScript, ShortcutKeysDriveTheInstrument) {
  auto d = driver();
  ASSERT_TRUE(d);
  ASSERT_TRUE(run(*d, "key Right\nkey shift+Left\n").ok);
  EXPECT_DOUBLE_EQ(d->app().scene().stage_deg, 14.0);  // −1 + 15
  ASSERT_TRUE(run(*d, "key C\n").ok);                  // conoscopic: condenser lens and Bertrand together
  EXPECT_EQ(d->app().scene().mode, ViewMode::Cono);
  EXPECT_TRUE(d->app().scene().bertrand_in);
  ASSERT_TRUE(run(*d, "key B\nkey A\nkey 4\nkey G\nkey G\n").ok);
  EXPECT_FALSE(d->app().scene().bertrand_in);
  EXPECT_FALSE(d->app().scene().analyzer_in);
  EXPECT_DOUBLE_EQ(d->app().scene().objective.na, 0.85);
  EXPECT_EQ(d->app().scene().compensator, Compensator::Mica);
  ASSERT_TRUE(run(*d, "key X\nkey Up\n").ok);  // cross, then turn the polarizer
  EXPECT_TRUE(d->app().scene().analyzer_in);
  EXPECT_DOUBLE_EQ(d->app().scene().analyzer_deg, 90.0);
  EXPECT_DOUBLE_EQ(d->app().scene().polarizer_deg, 5.0);
}

TEST(UiScript, BadInputRaisesTheBannerAndKeepsTheLastGoodScene) {
  auto d = driver();
  ASSERT_TRUE(d);
  testing::internal::CaptureStderr();
  const bool ok = run(*d, "set stage_deg=20\nset sample.thickness_um=-5\nexpect-error\nwait 2\n").ok;
  const std::string said = testing::internal::GetCapturedStderr();
  ASSERT_TRUE(ok);
  // An error provoked on purpose is one calm line, not reported as a failure.
  const auto calm = said.find("pmsim: expected error (test line 2): key 'sample.thickness_um'");
  EXPECT_NE(calm, std::string::npos) << said;
  EXPECT_EQ(said.find("pmsim: expected error", calm + 1), std::string::npos) << said;
  EXPECT_EQ(said.find("command line"), std::string::npos) << said;
  EXPECT_DOUBLE_EQ(d->app().scene().stage_deg, 20.0);
  EXPECT_DOUBLE_EQ(d->app().scene().sample.thickness_um, 30.0);
  EXPECT_NE(d->app().error().find("sample.thickness_um"), std::string::npos) << d->app().error();
  // The banner is drawn over the top of the field: red.
  const WindowPixels px = d->read_pixels();
  const Layout& l = d->app().layout();
  // A point of the banner below its two text lines and left of its button.
  const std::uint8_t* p =
      &px.rgb[(static_cast<size_t>(l.view.y + 70) * px.width + static_cast<int>(l.view.x + l.view.w * 0.6f)) *
              3];
  EXPECT_GT(p[0], 120);
  EXPECT_GT(p[0], 2 * p[1]);
  EXPECT_GT(p[0], 2 * p[2]);
  // Without expect-error the script stops at the bad line.
  const ScriptResult r = run(*d, "set sample.mineral=unobtainium\nset stage_deg=50\n");
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("line 1"), std::string::npos) << r.error;
  EXPECT_DOUBLE_EQ(d->app().scene().stage_deg, 20.0);
  // And an expected error that does not come is a failure too.
  EXPECT_FALSE(run(*d, "set stage_deg=10\nexpect-error\n").ok);
}

TEST(UiScript, ExportsAndScreenshotsCarryTheSceneAndSaveLoadRoundTrips) {
  auto d = driver();
  ASSERT_TRUE(d);
  const std::string field = out_path("field.png"), exr = out_path("field.exr"),
                    window = out_path("window.png"), scene = out_path("scene.json");
  for (const auto& f : {field, exr, window, scene}) std::filesystem::remove(f);
  const ScriptResult r = run(*d, "set stage_deg=33\nwait converged 60\nexport " + field + "\nexport " + exr +
                                     "\nscreenshot " + window + "\nsave " + scene + "\n");
  ASSERT_TRUE(r.ok) << r.error;
  const LoadedImage f = read_image(field);
  EXPECT_EQ(f.width, 48);
  ASSERT_TRUE(f.metadata.contains("pmsim:scene"));
  EXPECT_DOUBLE_EQ(f.metadata["pmsim:scene"]["stage_deg"].get<double>(), 33.0);
  const LoadedImage e = read_image(exr);
  EXPECT_EQ(e.width, 48);
  const LoadedImage w = read_image(window);
  EXPECT_EQ(w.width, 1280);
  EXPECT_EQ(w.height, 800);
  ASSERT_TRUE(run(*d, "set stage_deg=5\nload " + scene + "\n").ok);
  EXPECT_DOUBLE_EQ(d->app().scene().stage_deg, 33.0);
  // A folder that cannot exist (under a device file): banner, no crash, nothing written.
  EXPECT_TRUE(run(*d, "export /dev/null/x.png\nexpect-error\n").ok);
  for (const auto& path : {field, exr, window, scene}) std::filesystem::remove(path);
}

}  // namespace
}  // namespace pmsim::ui
