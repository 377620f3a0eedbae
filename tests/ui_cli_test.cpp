// The `pmsim` command line as a user runs it: headless screenshots, exit code 2 and no file on
// bad input, scripts, the frame-rate report.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/base/asset_locator.h"
#include "core/base/version.h"
#include "core/io/image_file.h"
#include "ui/about.h"

namespace {

const std::string kPmsim = std::string(PMSIM_BINARY_DIR) + "/app/pmsim";
const std::string kSmall = " --set render.width=48 --set render.height=48";

// One folder per test: ctest runs the tests of this file as parallel processes.
std::string kOut;

// The shell exits 2 itself when it cannot open the log (e.g. its folder removed under it), which
// would pass for pmsim's own exit 2: the log must exist and be new, or the run does not count.
int run(const std::string& args, std::string* output = nullptr) {
  const std::string log = kOut + "/log.txt";
  std::filesystem::remove(log);
  const int status = std::system((kPmsim + " " + args + " > " + log + " 2>&1").c_str());
  if (!std::filesystem::exists(log)) {
    ADD_FAILURE() << "the shell could not write " << log << " (pmsim did not run)";
    return -1;
  }
  if (output) {
    std::ifstream f(log);
    output->assign(std::istreambuf_iterator<char>(f), {});
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class UiCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::exists(kPmsim)) << "build the pmsim target first";
    kOut = std::string(PMSIM_BINARY_DIR) + "/ui_cli_test_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::remove_all(kOut);
    std::filesystem::create_directories(kOut);
  }
  void TearDown() override { std::filesystem::remove_all(kOut); }
};

// The About tab's version is the CMake project version (read back from this build's cache, the one
// place it is set) and it names the data folder the app is really using.
TEST(UiAbout, ShowsTheProjectVersionAndTheAssetFolderInUse) {
  std::ifstream cache(std::string(PMSIM_BINARY_DIR) + "/CMakeCache.txt");
  std::string line, project_version;
  const std::string key = "CMAKE_PROJECT_VERSION:STATIC=";
  while (std::getline(cache, line))
    if (line.rfind(key, 0) == 0) project_version = line.substr(key.size());
  ASSERT_FALSE(project_version.empty());
  EXPECT_EQ(pmsim::pmsim_version(), project_version);
  const std::vector<std::string> lines = pmsim::ui::about_lines();
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], "pmsim " + project_version);
  bool names_assets = false;
  for (const auto& l : lines) names_assets |= l.find(pmsim::asset_dir()) != std::string::npos;
  EXPECT_TRUE(names_assets);
  EXPECT_TRUE(std::filesystem::is_directory(pmsim::asset_dir() + "/materials")) << pmsim::asset_dir();
}

TEST_F(UiCli, HeadlessScreenshotIsTheWholeWindowWithTheSceneInItsMetadata) {
  const std::string png = kOut + "/shot.png";
  std::string out;
  ASSERT_EQ(run("--headless" + kSmall + " --set stage_deg=12 --screenshot " + png, &out), 0) << out;
  const pmsim::LoadedImage img = pmsim::read_image(png);
  EXPECT_EQ(img.width, 1280);
  EXPECT_EQ(img.height, 800);
  ASSERT_TRUE(img.metadata.contains("pmsim:scene"));
  EXPECT_DOUBLE_EQ(img.metadata["pmsim:scene"]["stage_deg"].get<double>(), 12.0);
}

TEST_F(UiCli, BadInputExitsWith2NamingTheKeyAndWritesNothing) {
  const std::string png = kOut + "/bad.png";
  std::string out;
  EXPECT_EQ(run("--headless" + kSmall + " --set objective.na=3 --screenshot " + png, &out), 2);
  EXPECT_NE(out.find("objective.na"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(png));
  EXPECT_EQ(run("--headless --set nosuchkey=1 --screenshot " + png, &out), 2);
  EXPECT_NE(out.find("nosuchkey"), std::string::npos) << out;
  EXPECT_EQ(run("--headless " + kOut + "/missing-scene.json --screenshot " + png, &out), 2);
  EXPECT_NE(out.find("missing-scene.json"), std::string::npos) << out;
  EXPECT_EQ(run("--headless --frames many --screenshot " + png), 2);
  EXPECT_EQ(run("--headless"), 2);  // nothing to produce
  EXPECT_FALSE(std::filesystem::exists(png));
}

TEST_F(UiCli, ScriptsRunAndABadScriptLineExitsWith2) {
  const std::string script = kOut + "/s.pmsim", shot = kOut + "/scripted.png";
  std::ofstream(script) << "set render.width=48\nset render.height=48\nkey C\nwait converged 60\n"
                           "screenshot "
                        << shot << "\n";
  std::string out;
  ASSERT_EQ(run("--headless --script " + script, &out), 0) << out;
  const pmsim::LoadedImage img = pmsim::read_image(shot);
  EXPECT_EQ(img.metadata["pmsim:scene"]["mode"], "cono");
  std::ofstream(script) << "wait 1\nteleport 3 4\n";
  EXPECT_EQ(run("--headless --script " + script, &out), 2);
  EXPECT_NE(out.find("line 2"), std::string::npos) << out;
}

TEST_F(UiCli, ReportsTheMeasuredFrameRate) {
  std::string out;
  ASSERT_EQ(run("--headless" + kSmall + " --frames 20 --no-settle --report-fps", &out), 0) << out;
  EXPECT_NE(out.find("ui_fps="), std::string::npos) << out;
  EXPECT_NE(out.find("frames=20"), std::string::npos) << out;
  std::printf("%s", out.c_str());
}

}  // namespace
