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
  // A fixed sample count with no estimate: stopped by the count, not claimed converged.
  EXPECT_TRUE(j["error_estimate"].is_null());
  EXPECT_EQ(j["stopped"], "cap");
  EXPECT_EQ(j["converged"], false);
  // A bad value at a 3-D dot path is an input error of the 3-D parser: exit 2, no file.
  const std::string bad = temp_dir() + "/fig3_bad.png";
  EXPECT_EQ(run(scene + " --set camera.width=-5 --out " + bad), 2);
  EXPECT_EQ(run(scene + " --set camera.width.x=5 --out " + bad), 2);
  EXPECT_FALSE(fs::exists(bad));
}

// --scale-bar burns the bar into the exported image and changes nothing else of it. The basalt
// scene at 10×, field number 20: a 2 mm field over the 72-pixel short side, 2/72 mm per pixel; the
// longest 1-2-5 length within a quarter of the 96-pixel width (0.667 mm) is 0.5 mm = 18 pixels.
TEST(RenderCli, ScaleBarIsBurnedIntoTheExportOnly) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const std::string scene = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/basalt_section_ortho.json";
  // One pass of the traced slab (the section between crossed polars with relief, 18 paths a
  // pixel): the bar does not depend on the paths, and 256 of them took 13 s for the two renders.
  const std::string size =
      " --set render.width=96 --set render.height=72 --set eyepiece.field_number_mm=20 --set render.spp=18";
  const std::string plain = temp_dir() + "/plain.exr", barred = temp_dir() + "/barred.exr";
  ASSERT_EQ(run(scene + size + " --out " + plain), 0);
  ASSERT_EQ(run(scene + size + " --scale-bar --out " + barred), 0);
  const pmsim::LoadedImage a = pmsim::read_image(plain), b = pmsim::read_image(barred);
  ASSERT_EQ(a.width, 96);
  ASSERT_EQ(b.height, 72);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  const int ch = a.channels;
  int changed = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = (static_cast<std::size_t>(y) * a.width + x) * ch + c;
        if (a.pixels[i] == b.pixels[i]) continue;
        ++changed;
        // The bar and its label sit bottom left (8-pixel margin, 7-pixel text): nothing else moves.
        EXPECT_LT(x, a.width / 2) << y;
        EXPECT_GE(y, a.height / 2) << x;
      }
  EXPECT_GT(changed, 0);
  // The bar: 2 rows (52, 53 for a 72-row image: 72 − 8 margin − 7 text − 3 gap − 2), white from
  // x = 8 for exactly the 18 pixels worked out above, black outline after it.
  auto white = [&](int x, int y) {
    const std::size_t i = (static_cast<std::size_t>(y) * b.width + x) * ch;
    return b.pixels[i] == 1.0f && b.pixels[i + 1] == 1.0f && b.pixels[i + 2] == 1.0f;
  };
  int run_px = 0;
  while (white(8 + run_px, 52)) ++run_px;
  EXPECT_EQ(run_px, 18);
  EXPECT_FALSE(white(7, 52));
  // A conoscopic image measures directions, not lengths: bad input, exit 2, no file.
  const std::string cono = temp_dir() + "/cono.exr";
  EXPECT_EQ(run(std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/calcite_cono.json --scale-bar --out " + cono), 2);
  EXPECT_FALSE(fs::exists(cono));
}
