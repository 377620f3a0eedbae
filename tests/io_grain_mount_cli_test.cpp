// The grain-mount keys of issue 12 through the scene reader and pmsim-render: focus_um,
// condenser.aperture_na, sample.type=grains and sample.medium_index; bad values exit 2 naming the
// key and the value, and a grain mount renders.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/io/image_file.h"
#include "core/io/scene_file.h"
#include "render_cli_run.h"

namespace fs = std::filesystem;
using namespace pmsim;

namespace {
const std::string kBinary = test::kRenderBinary;

std::string temp_dir() { return test::cli_temp_dir("grain_mount_test"); }

using test::CliRun;
CliRun run(const std::string& args) { return test::run_render_cli(args, temp_dir()); }
const std::string kSmall = " --set render.width=16 --set render.height=16 --set render.spp=2 ";
}  // namespace

TEST(GrainMountCli, BadValuesExitTwoNamingKeyAndValue) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const std::string out = temp_dir() + "/bad.png";
  for (const auto& [set, key, value] :
       {std::tuple{"sample.medium_index=1.9", "sample.medium_index", "1.9"},
        std::tuple{"sample.medium_index=1.3999", "sample.medium_index", "1.3999"},
        std::tuple{"focus_um=5000", "focus_um", "5000"},
        std::tuple{"condenser.aperture_na=0.95", "condenser.aperture_na", "0.95"},
        std::tuple{"sample.type=grain", "sample.type", "grain"}}) {
    const CliRun r = run(std::string("--set sample.type=grains --set ") + set + kSmall + "--out " + out);
    EXPECT_EQ(r.code, 2) << set;
    EXPECT_NE(r.err.find(key), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(value), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << set;
  }
}

TEST(GrainMountCli, GrainMountRendersAPlaneLightImage) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const std::string out = temp_dir() + "/grains.png";
  const CliRun r = run("--set sample.type=grains --set sample.mineral=garnet --set sample.medium_index=1.54 "
                       "--set focus_um=5 --set condenser.aperture_na=0.1 --set analyzer=out" + kSmall + "--out " + out);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out));
}

// Calcite fragments with the analyzer in: the interference image, not the plane-light one. The
// liquid between the fragments is extinct between crossed polars (median pixel dark), while in
// plane light it is the bright empty field; the fragments, of retardations from first-order
// colours at their thin edges to high-order white, light up (a few % of the pixels at least: the
// mount covers 25% of the slide and only fragments with an optic axis near vertical stay dark).
TEST(GrainMountCli, CalciteWithTheAnalyzerInShowsInterferenceNotPlaneLight) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const auto luminance = [](const LoadedImage& im) {
    std::vector<double> y;
    for (int i = 0; i < im.width * im.height; ++i)
      y.push_back(0.2126 * im.pixels[3 * i] + 0.7152 * im.pixels[3 * i + 1] + 0.0722 * im.pixels[3 * i + 2]);
    return y;
  };
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const std::string common = "--set sample.type=grains --set sample.mineral=calcite --set render.width=64 "
                             "--set render.height=64 --set render.spp=64 ";
  const std::string crossed = temp_dir() + "/calcite_crossed.png", plane = temp_dir() + "/calcite_plane.png";
  CliRun r = run(common + "--set analyzer=in --set analyzer_deg=90 --out " + crossed);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("note"), std::string::npos) << "no 'analyzer ignored' note any more: " << r.err;
  r = run(common + "--set analyzer=out --out " + plane);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<double> yc = luminance(read_image(crossed)), yp = luminance(read_image(plane));
  ASSERT_EQ(yc.size(), 64u * 64u);
  EXPECT_LT(median(yc), 0.05) << "the liquid between crossed polars is dark";
  EXPECT_GT(median(yp), 0.7) << "the liquid in plane light is the bright empty field";
  const double lit = double(std::count_if(yc.begin(), yc.end(), [](double v) { return v > 0.2; })) / yc.size();
  RecordProperty("crossed_lit_fraction", std::to_string(lit));
  EXPECT_GT(lit, 0.02) << "calcite fragments light up between crossed polars";
}

TEST(GrainMountKeys, SurviveSaveAndLoad) {
  Scene s;
  apply_settings(s, {"sample.type=grains", "sample.medium_index=1.662", "focus_um=-7.5", "condenser.aperture_na=0.2"});
  const std::string file = temp_dir() + "/scene.json";
  save_scene_file(s, file);
  const Scene t = load_scene_file(file);
  EXPECT_EQ(t.sample.type, SampleType::Grains);
  ASSERT_TRUE(t.sample.medium_index);
  EXPECT_EQ(*t.sample.medium_index, 1.662);
  EXPECT_EQ(t.focus_um, -7.5);
  EXPECT_EQ(t.condenser.aperture_na, 0.2);
  // Unset, the liquid index is not written (a saved scene of before issue 12 reads back the same).
  const nlohmann::json j = scene_to_json(Scene{});
  EXPECT_FALSE(j["sample"].contains("medium_index"));
}

// --labels and --grains on a grain mount (issue 23): the fragment under every pixel, and the file
// lists exactly the fragments the labels show, with their areas; a section-only scene key is not
// needed. The physics of the numbers: tests/specimen_grain_mount_truth_test.cpp.
TEST(GrainMountCli, LabelsAndGrainsNameTheFragmentsInTheImage) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const std::string dir = temp_dir();
  const CliRun r = run("--set sample.type=grains --set sample.mineral=calcite --set sample.medium_index=1.54" + kSmall +
                       "--out " + dir + "/g.png --labels " + dir + "/l.png --grains " + dir + "/g.json");
  ASSERT_EQ(r.code, 0) << r.err;
  const LoadedImage img = read_image(dir + "/l.png");
  ASSERT_EQ(img.channels, 1);
  std::map<int, long long> counts;
  for (float v : img.pixels)
    if (const int l = int(std::lround(v * 65535.0f)); l != 0) ++counts[l];
  std::ifstream in(dir + "/g.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["sample"], "grains");
  EXPECT_DOUBLE_EQ(j["liquid_n_d"].get<double>(), 1.54);
  std::map<int, long long> listed;
  for (const auto& g : j["grains"]) {
    listed[g["id"].get<int>()] = g["area_px"].get<long long>();
    EXPECT_EQ(g["mineral"], "calcite");
    EXPECT_TRUE(g["relief_vs_medium"] == "higher" || g["relief_vs_medium"] == "lower" ||
                g["relief_vs_medium"] == "matched");
  }
  EXPECT_FALSE(listed.empty());
  EXPECT_EQ(listed, counts);
}
