// The mechanical stage in the app: a right-button drag moves the section with the cursor, Ctrl +
// arrows step a tenth of the field, the turret changes the field of view, and field exports carry
// a scale bar as long as its label says (and, with render.native=on on an EBSD map, one pixel per
// map point).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/ebsd/example_map.h"
#include "core/ebsd/map_writer.h"
#include "core/io/image_file.h"
#include "core/microscope/view_geometry.h"
#include "core/render/scale_bar.h"
#include "ui/headless_driver.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

std::unique_ptr<HeadlessDriver> section_driver() {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.render.width = s.render.height = 64;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  EXPECT_TRUE(d) << log;
  return d;
}

ScriptResult run(UiDriver& d, const std::string& text) {
  return run_script(d, parse_script(text, "test.pmsim"), "test.pmsim");
}

TEST(UiStage, RightDragMovesTheSectionWithTheCursor) {
  auto d = section_driver();
  ASSERT_TRUE(d);
  // 10× with field number 20: the square image spans 2 mm. Dragging a quarter of the field to the
  // right brings section points from the left under the crosshair: x decreases by 0.5 mm. ImGui
  // floors mouse positions to whole pixels: two pixels of the field square (~600 px) are ≤ 0.01 mm.
  ASSERT_TRUE(run(*d, "pan 0.25 0\n").ok);
  EXPECT_NEAR(d->app().scene().stage.x_mm, -0.5, 0.01);
  EXPECT_NEAR(d->app().scene().stage.y_mm, 0.0, 0.01);
  EXPECT_NEAR(d->app().scene().stage_deg, 0.0, 1e-12);  // a translation, not a turn
  // Dragging down brings northern points in: y grows (screen y points south).
  ASSERT_TRUE(run(*d, "pan 0 0.1\n").ok);
  EXPECT_NEAR(d->app().scene().stage.y_mm, 0.2, 0.01);
}

TEST(UiStage, RightDragOnATurnedStageFollowsTheCursorNotTheSectionAxes) {
  auto d = section_driver();
  ASSERT_TRUE(d);
  ASSERT_TRUE(run(*d, "set stage_deg=90\npan 0.25 0\n").ok);
  // The section is turned 90° counter-clockwise: a section point p shows at R(+90°)(p − c), so the
  // point under the cursor stays there when c moves by −R(−90°)(0.5, 0) = (0, +0.5) mm.
  EXPECT_NEAR(d->app().scene().stage.x_mm, 0.0, 0.01);
  EXPECT_NEAR(d->app().scene().stage.y_mm, 0.5, 0.01);
}

TEST(UiStage, CtrlArrowsStepATenthOfTheFieldAndTheTurretSetsTheField) {
  auto d = section_driver();
  ASSERT_TRUE(d);
  ASSERT_TRUE(run(*d, "key 3\nkey ctrl+Right\n").ok);  // 40×: 0.5 mm field, a step of 0.05 mm
  EXPECT_NEAR(field_of_view_mm(d->app().scene()), 0.5, 1e-12);
  EXPECT_NEAR(d->app().scene().stage.x_mm, 0.05, 1e-12);
  ASSERT_TRUE(run(*d, "key 1\nkey ctrl+Up\n").ok);  // 4×: 5 mm field, 0.5 mm north
  EXPECT_NEAR(field_of_view_mm(d->app().scene()), 5.0, 1e-12);
  EXPECT_NEAR(d->app().scene().stage.y_mm, 0.5, 1e-12);
  ASSERT_TRUE(run(*d, "key ctrl+0\n").ok);
  EXPECT_EQ(d->app().scene().stage.x_mm, 0.0);
  EXPECT_EQ(d->app().scene().stage.y_mm, 0.0);
}

TEST(UiStage, FieldExportCarriesAScaleBarOfTheRightLength) {
  auto d = section_driver();
  ASSERT_TRUE(d);
  const std::string path = std::string(PMSIM_BINARY_DIR) + "/ui_stage_translation_bar.png";
  std::filesystem::remove(path);
  // The bar does not depend on the renderer: the flat section image (optics.relief off) converges
  // in about a second, where the traced slab between crossed polars takes ~90 s at 256².
  const std::string script = "set optics.relief=off\nset render.width=256\nset render.height=256\n"
                             "wait converged\nexport " + path + "\n";
  ASSERT_TRUE(run(*d, script).ok);
  const LoadedImage im = read_image(path);
  // The bar is the longest run of pure white on a row (PNG: sRGB 1.0 → 255 exactly); its length
  // the one choose_scale_bar gives for 2 mm over 256 px (a 0.5 mm bar, 64 px), to the rounding
  // of length_px (±0.5 px).
  const ScaleBar want = choose_scale_bar(2.0 / 256, 256);
  int longest = 0;
  for (int y = 0; y < im.height; ++y) {
    int run_px = 0;
    for (int x = 0; x < im.width; ++x) {
      const float* p = &im.pixels[(static_cast<std::size_t>(y) * im.width + x) * im.channels];
      run_px = (p[0] >= 0.999f && p[1] >= 0.999f && p[2] >= 0.999f) ? run_px + 1 : 0;
      longest = std::max(longest, run_px);
    }
  }
  EXPECT_NEAR(longest, want.length_px, 0.5);
}

TEST(UiStage, NativeFieldExportOfAnEbsdMapHasOnePixelPerPoint) {
  const std::string map = std::string(PMSIM_BINARY_DIR) + "/ui_stage_translation_native.ctf";
  const std::string path = std::string(PMSIM_BINARY_DIR) + "/ui_stage_translation_native.png";
  write_ctf(example_quartzite_map(48, 20, 10.0), map);
  std::filesystem::remove(path);
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = map;
  s.render.width = s.render.height = 64;
  s.render.native = true;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  ASSERT_TRUE(run(*d, "wait converged\nexport " + path + "\n").ok);
  // The export: the map's 48 columns × 20 rows (square steps), as pmsim-render writes it; the
  // view keeps its 64² image.
  const LoadedImage im = read_image(path);
  EXPECT_EQ(im.width, 48);
  EXPECT_EQ(im.height, 20);
  EXPECT_EQ(d->app().image().width, 64);
  EXPECT_EQ(d->app().image().height, 64);
}

}  // namespace
}  // namespace pmsim
