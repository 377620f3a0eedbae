// The built pmsim-render against its contract: exit codes, no output left on bad input, stats keys.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/io/image_file.h"

namespace fs = std::filesystem;

namespace {
const std::string kBinary = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-render";

int run(const std::string& args) {
  const int status = std::system((kBinary + " " + args + " 2>/dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
std::string temp_dir() {
  const auto d = fs::temp_directory_path() / ("pmsim_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d.string();
}
}  // namespace

TEST(RenderCli, BadInputExitsTwoAndLeavesNoOutput) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const std::string out = temp_dir() + "/bad.png";
  EXPECT_EQ(run("--set sample.thickness_um=-1 --out " + out), 2);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run("/nonexistent/scene.json --out " + out), 2);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run("--set sample.type=plate --set sample.mineral=unobtainium --out " + out), 2);
  EXPECT_EQ(run("--set objective.na=2 --out " + out), 2);
  EXPECT_EQ(run("--out " + temp_dir() + "/x.bmp"), 2);
  EXPECT_EQ(run(""), 2);  // --out is required
  EXPECT_FALSE(fs::exists(out));
  // A bad key in the scene file: the message names it; still exit 2.
  const std::string scene = temp_dir() + "/bad_scene.json";
  std::ofstream(scene) << R"({"objective": {"na": "wide"}})";
  EXPECT_EQ(run(scene + " --out " + out), 2);
  EXPECT_FALSE(fs::exists(out));
}

TEST(RenderCli, RendersASmallSceneWithStats) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const std::string out = temp_dir() + "/ok.exr", stats = temp_dir() + "/ok.json";
  EXPECT_EQ(run(std::string(PMSIM_SOURCE_DIR) +
                "/assets/scenes/calcite_cono.json --set render.width=32 --set render.height=32 --out " + out +
                " --stats " + stats),
            0);
  EXPECT_TRUE(fs::exists(out));
  std::ifstream f(stats);
  const nlohmann::json j = nlohmann::json::parse(f);
  for (const char* k : {"time_ms", "samples_per_pixel", "wavelengths", "error_estimate", "model_report"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_LT(j["error_estimate"].get<double>(), 0.5);  // rendered to convergence
}

TEST(RenderCli, AScene3dFileGoesToThe3dRendererWithSetOnItsDotPaths) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const std::string out = temp_dir() + "/fig3.exr", stats = temp_dir() + "/fig3.json";
  const std::string scene = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes3d/fig3_lens_point_light.json";
  EXPECT_EQ(run(scene + " --set camera.width=40 --set camera.height=30 --set render.wavelengths=8 --out " +
                out + " --stats " + stats),
            0);
  const pmsim::LoadedImage img = pmsim::read_image(out);
  // The --set values reached the 3-D scene: the image has the size they ask for.
  EXPECT_EQ(img.width, 40);
  EXPECT_EQ(img.height, 30);
  ASSERT_TRUE(img.metadata.contains("pmsim:scene"));
  EXPECT_EQ(img.metadata["pmsim:scene"]["type"], "scene3d");
  EXPECT_EQ(img.metadata["pmsim:scene"]["scene"]["camera"]["width"], 40);
  // The lit striped plane fills most of the view: the image cannot be black.
  double sum = 0.0;
  for (float v : img.pixels) {
    ASSERT_TRUE(std::isfinite(v));
    sum += v;
  }
  EXPECT_GT(sum / img.pixels.size(), 0.01);
  std::ifstream f(stats);
  const nlohmann::json j = nlohmann::json::parse(f);
  for (const char* k : {"time_ms", "samples_per_pixel", "wavelengths", "error_estimate"})
    EXPECT_TRUE(j.contains(k)) << k;
  // A bad value at a 3-D dot path is an input error of the 3-D parser: exit 2, no file.
  const std::string bad = temp_dir() + "/fig3_bad.png";
  EXPECT_EQ(run(scene + " --set camera.width=-5 --out " + bad), 2);
  EXPECT_EQ(run(scene + " --set camera.width.x=5 --out " + bad), 2);
  EXPECT_FALSE(fs::exists(bad));
}
