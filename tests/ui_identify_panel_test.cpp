// The app's Identify tab (issue 23): pmsim-exercise identify's determinative aid, driven by the
// script's `identify KEY VALUE` as a student's choices would be; the candidates are core's
// identify() of the same observations (the tab matches nothing itself), and the tab is drawn (the
// left panel's pixels change when it comes to the front and again when the candidates change).
// And the teaching panel's compensator test by brightness: the line it shows for a grain.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/base/input_error.h"
#include "core/exercise/identify.h"
#include "core/exercise/mineral_signature.h"
#include "core/render/brightness_test.h"
#include "ui/headless_driver.h"
#include "ui/script.h"
#include "ui/teaching.h"

namespace pmsim::ui {
namespace {

constexpr int kW = 1280, kH = 800;

ScriptResult run(UiDriver& d, const std::string& text) { return run_script(d, parse_script(text, "test"), "test"); }

std::vector<std::string> names(const std::vector<Candidate>& cs) {
  std::vector<std::string> n;
  for (const auto& c : cs) n.push_back(c.mineral);
  return n;
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

// Pixels of the left panel that differ between two frames (any channel by more than 8).
long changed_pixels(const WindowPixels& a, const WindowPixels& b, const Rect& r) {
  long n = 0;
  for (int y = std::max(0, int(r.y)); y < std::min(a.height, int(r.y + r.h)); ++y)
    for (int x = std::max(0, int(r.x)); x < std::min(a.width, int(r.x + r.w)); ++x) {
      const std::size_t i = (std::size_t(y) * a.width + x) * 3;
      for (int k = 0; k < 3; ++k)
        if (std::abs(int(a.rgb[i + k]) - int(b.rgb[i + k])) > 8) {
          ++n;
          break;
        }
    }
  return n;
}

WindowPixels shot(UiDriver& d) {
  d.frame();
  return d.read_pixels();
}

TEST(UiIdentifyPanel, QuartzObservationsByScriptGiveCoresCandidatesAndDrawTheTab) {
  Scene s;
  s.render.width = s.render.height = 64;  // the test is about the panel, not the image
  s.sample_in = false;
  std::string log;
  auto d = HeadlessDriver::create(s, kW, kH, log);
  ASSERT_TRUE(d) << log;
  App& app = d->app();
  // Nothing observed: every library mineral fits.
  EXPECT_EQ(app.identify_candidates().size(), library_signatures().size());
  const Rect controls = app.layout().controls;
  d->frame();
  const WindowPixels microscope_tab = shot(*d);

  // What a student sees of quartz.
  ScriptResult r = run(*d,
                       "identify character uniaxial\nidentify sign positive\nidentify order 1\n"
                       "identify relief low\nidentify coloured no\n");
  ASSERT_TRUE(r.ok) << r.error;
  const auto found = names(app.identify_candidates());
  EXPECT_TRUE(has(found, "quartz"));
  EXPECT_FALSE(has(found, "calcite"));
  EXPECT_LT(found.size(), library_signatures().size());
  // A thin client: the same list as core's for the same observations, with the same reasons.
  Observations o;
  for (const auto& [k, v] : std::vector<std::pair<std::string, std::string>>{
           {"character", "uniaxial"}, {"sign", "positive"}, {"order", "1"}, {"relief", "low"}, {"coloured", "no"}})
    o = parse_observation(o, k, v);
  const auto core = identify(o);
  EXPECT_EQ(found, names(core));
  ASSERT_FALSE(app.identify_candidates().empty());
  EXPECT_EQ(app.identify_candidates()[0].why, core[0].why);

  // The tab came to the front: the left panel is drawn anew.
  const WindowPixels quartz_tab = shot(*d);
  const long tab_changed = changed_pixels(microscope_tab, quartz_tab, controls);
  EXPECT_GT(tab_changed, 2000) << "the Identify tab did not replace the Microscope tab";

  // A word core refuses raises the banner and changes nothing; an unknown key stops the parse.
  r = run(*d, "identify relief enormous\nexpect-error\n");
  ASSERT_TRUE(r.ok) << r.error;
  app.clear_error();
  EXPECT_EQ(names(app.identify_candidates()), found);
  EXPECT_EQ(app.identify_observations().at("relief"), "low");
  EXPECT_THROW(parse_script("identify colour no\n", "test"), InputError);
  EXPECT_THROW(parse_script("identify clear now\n", "test"), InputError);

  // A key without a value clears it; `identify clear` clears them all (all 54 back in the list).
  r = run(*d, "identify coloured\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(app.identify_observations().count("coloured"), 0u);
  EXPECT_GE(app.identify_candidates().size(), found.size());
  r = run(*d, "identify clear\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(app.identify_observations().empty());
  EXPECT_EQ(app.identify_candidates().size(), library_signatures().size());
  const WindowPixels all_tab = shot(*d);
  const long list_changed = changed_pixels(quartz_tab, all_tab, controls);
  EXPECT_GT(list_changed, 500) << "the candidate list was not redrawn";
  std::printf("identify tab: %zu of %zu candidates for quartz's observations; %ld panel pixels changed on "
              "selecting the tab, %ld on clearing\n",
              found.size(), library_signatures().size(), tab_changed, list_changed);
}

TEST(UiIdentifyPanel, TeachingPanelBrightnessLineIsCoresReading) {
  // A first-order grey (100 nm): the mica plate brightens it on addition, darkens it on subtraction.
  for (const double gamma : {100.0, 273.0, 450.0, 900.0})
    for (const Compensator c : {Compensator::Mica, Compensator::Gypsum}) {
      const BrightnessTest t = brightness_test(gamma, c);
      const std::string line = brightness_line(gamma, c);
      EXPECT_NE(line.find(c == Compensator::Mica ? "Mica λ/4 at 45°" : "Gypsum λ at 45°"), std::string::npos) << line;
      EXPECT_NE(line.find(": " + t.reading), std::string::npos) << line;
      char y[64];
      std::snprintf(y, sizeof y, "Y %.2f → %.2f adding, %.2f subtracting", t.y_alone, t.y_addition, t.y_subtraction);
      EXPECT_NE(line.find(y), std::string::npos) << line;
    }
  const std::string mica = brightness_line(100.0, Compensator::Mica);
  EXPECT_NE(mica.find("brighter on addition"), std::string::npos) << mica;
  std::printf("%s\n%s\n", mica.c_str(), brightness_line(100.0, Compensator::Gypsum).c_str());
}

}  // namespace
}  // namespace pmsim::ui
