// The app's file dialog: the folder listing it shows, and opening an EBSD map from it the way a
// user does (type the path into its location field, Enter), which puts the map on the stage.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/base/asset_locator.h"
#include "core/ebsd/read_orientation_map.h"
#include "ui/file_browser.h"
#include "ui/headless_driver.h"

#include <GLFW/glfw3.h>

namespace pmsim::ui {
namespace {
namespace fs = std::filesystem;

TEST(FileBrowser, ListsFoldersThenTheFilesItOpensSortedAndSkipsHiddenOnes) {
  const fs::path dir = fs::temp_directory_path() / ("pmsim_browser_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "maps");
  fs::create_directories(dir / ".cache");
  for (const char* f : {"b.ctf", "A.ANG", "notes.txt", "granite.json", ".hidden.json"}) std::ofstream(dir / f) << "x";
  std::string error;
  const auto entries = list_directory(dir.string(), {".json", ".ctf", ".ang"}, error);
  EXPECT_TRUE(error.empty()) << error;
  ASSERT_EQ(entries.size(), 4u);  // maps/, then A.ANG (extension matched without case), b.ctf, granite.json
  EXPECT_EQ(entries[0].name, "maps");
  EXPECT_TRUE(entries[0].is_directory);
  EXPECT_EQ(entries[1].name, "A.ANG");
  EXPECT_EQ(entries[2].name, "b.ctf");
  EXPECT_EQ(entries[3].name, "granite.json");
  EXPECT_FALSE(entries[3].is_directory);

  const auto none = list_directory((dir / "missing").string(), {".json"}, error);
  EXPECT_TRUE(none.empty());
  EXPECT_NE(error.find("missing"), std::string::npos) << error;  // the message names the folder
  fs::remove_all(dir);
}

TEST(FileBrowser, TypingAMapPathAndEnterPutsTheMapOnTheStage) {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.render.width = s.render.height = 64;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  ASSERT_TRUE(d->frame());

  // Escape closes the dialog and changes nothing.
  d->app().browse(App::Browse::Section);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(d->frame());
  EXPECT_TRUE(d->app().browsing());
  d->inject_key(GLFW_KEY_ESCAPE, false, false);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(d->frame());
  EXPECT_FALSE(d->app().browsing());
  EXPECT_EQ(d->app().scene().sample.section, "granite_hand_placed");

  // The dialog opens in the current section's folder (assets/sections); a relative path typed
  // into its location field is taken from there, so this reaches the shipped map next door.
  d->app().browse(App::Browse::Section);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(d->frame());
  d->inject_text("../ebsd/quartzite_example.ctf");
  ASSERT_TRUE(d->frame());
  d->inject_key(GLFW_KEY_ENTER, false, false);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(d->frame());
  EXPECT_FALSE(d->app().browsing());
  const std::string chosen = d->app().scene().sample.section;
  EXPECT_TRUE(is_orientation_map_path(chosen)) << chosen;
  std::error_code ec;
  EXPECT_TRUE(fs::equivalent(chosen, fs::path(asset_dir()) / "ebsd" / "quartzite_example.ctf", ec)) << chosen;
  EXPECT_TRUE(d->app().error().empty()) << d->app().error();
  EXPECT_TRUE(d->app().wait_rendered(60.0));
}

}  // namespace
}  // namespace pmsim::ui
