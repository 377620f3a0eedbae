// pmsim-render on EBSD maps (issue 13): a scene whose sample.section is a .ctf or .ang file the
// test writes. Bad maps and unmapped phases exit 2 naming what is wrong and write nothing;
// --labels and --grains give the reconstructed grains; render.native=on gives one pixel per point.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "core/base/units.h"
#include "core/ebsd/map_writer.h"
#include "core/io/image_file.h"
#include "tests/reliability_support.h"

using namespace pmsim;
using namespace pmsim::reliability;

namespace {

const std::string kRender = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-render";

// Columns of grains three points wide (each its own orientation, > 10° apart), quartz, 20 µm
// steps; phase 2 "Unobtainium 7" at point 0 when `odd_phase`.
OrientationMap stripes(int columns, int rows, bool odd_phase) {
  OrientationMap m;
  m.vendor = EbsdVendor::OxfordChannel5;
  m.columns_odd = m.columns_even = columns;
  m.rows = rows;
  m.step_x_um = m.step_y_um = 20.0;
  m.phases = {EbsdPhase{1, "Quartz", "SiO2", UnitCell{4.913, 4.913, 5.405, 90, 90, 120}, CrystalSystem::Trigonal,
                        "-3m", "7", 154},
              EbsdPhase{2, "Unobtainium 7", "", UnitCell{5, 5, 5, 90, 90, 90}, CrystalSystem::Cubic, "m-3m", "11", 225}};
  m.allocate_points();
  for (std::size_t i = 0; i < m.size(); ++i) {
    const int c = static_cast<int>(i % columns);
    m.phase[i] = 1;
    m.phi1_rad[i] = static_cast<float>(radians(90.0));
    m.Phi_rad[i] = static_cast<float>(radians(20.0 + 25.0 * (c / 3)));
  }
  if (odd_phase) m.phase[0] = 2;
  return m;
}

std::string scene_file(const ScratchDir& dir, const std::string& map) {
  return dir.file("s.json", nlohmann::json{{"type", "microscope"},
                                           {"sample", {{"type", "section"}, {"section", map}}},
                                           {"render", {{"width", 24}, {"height", 24}, {"spp", 1}, {"wavelengths", 8}}}}
                                .dump());
}

std::vector<std::string> args(const std::string& scene, const std::vector<std::string>& extra) {
  std::vector<std::string> a = {kRender, scene};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

bool nothing_written(const ScratchDir& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    const std::string n = e.path().filename().string();
    if (n != "s.json" && n.find(".ctf") == std::string::npos && n[0] != '.') return false;
  }
  return true;
}

}  // namespace

TEST(EbsdMapCli, UnmappedPhaseExitsTwoNamingItAndHowToMapIt) {
  ScratchDir dir;
  write_ctf(stripes(9, 6, true), dir / "m.ctf");
  const std::string scene = scene_file(dir, dir / "m.ctf");
  const CommandResult r = run_command(args(scene, {"--out", dir / "a.png", "--labels", dir / "l.png"}), dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("Unobtainium 7"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sample.phases"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("m.ctf"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_written(dir));
  // Mapped with --set it renders.
  const CommandResult ok = run_command(
      args(scene, {"--set", R"(sample.phases={"Unobtainium 7": "almandine"})", "--out", dir / "a.png"}), dir);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "a.png"));
}

TEST(EbsdMapCli, MalformedOrTruncatedFileExitsTwoNamingFileLineAndField) {
  ScratchDir dir;
  write_ctf(stripes(9, 6, false), dir / "good.ctf");
  std::string text = read_file(dir / "good.ctf");
  // The last data line cut in the middle of a number (a map cropped in an editor mid-line).
  text.erase(text.size() - 12);
  { std::ofstream(dir / "cut.ctf", std::ios::binary) << text; }
  const CommandResult r = run_command(args(scene_file(dir, dir / "cut.ctf"), {"--out", dir / "a.png"}), dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("cut.ctf"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("line "), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_written(dir));
  // A bad number in a field.
  std::string bad = read_file(dir / "good.ctf");
  const auto at = bad.rfind("\n1\t");
  ASSERT_NE(at, std::string::npos);
  bad[at + 1] = 'x';  // one character (replace(…, "x") trips GCC 12's false -Wrestrict)
  { std::ofstream(dir / "bad.ctf", std::ios::binary) << bad; }
  const CommandResult b = run_command(args(scene_file(dir, dir / "bad.ctf"), {"--out", dir / "a.png"}), dir);
  EXPECT_EQ(b.exit_code, 2) << b.err;
  EXPECT_NE(b.err.find("bad.ctf"), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("Phase"), std::string::npos) << "the field, by its column name: " << b.err;
  // Whole lines missing: it renders what it holds, with a warning giving both counts.
  std::string whole = read_file(dir / "good.ctf");
  whole.erase(whole.rfind('\n', whole.size() - 2) + 1);
  { std::ofstream(dir / "short.ctf", std::ios::binary) << whole; }
  const CommandResult w = run_command(args(scene_file(dir, dir / "short.ctf"), {"--out", dir / "a.png"}), dir);
  EXPECT_EQ(w.exit_code, 0) << w.err;
  EXPECT_NE(w.err.find("54"), std::string::npos) << w.err;
  EXPECT_NE(w.err.find("53"), std::string::npos) << w.err;
}

TEST(EbsdMapCli, LabelsAndGrainsAreTheReconstructedGrainsAtNativeResolution) {
  ScratchDir dir;
  write_ctf(stripes(12, 5, false), dir / "m.ctf");
  const CommandResult r = run_command(args(scene_file(dir, dir / "m.ctf"),
                                           {"--set", "render.native=on", "--out", dir / "a.png", "--labels",
                                            dir / "l.png", "--grains", dir / "g.json", "--stats", dir / "st.json"}),
                                      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const LoadedImage img = read_image(dir / "a.png");
  EXPECT_EQ(img.width, 12);  // one pixel per point
  EXPECT_EQ(img.height, 5);
  const LoadedImage l = read_image(dir / "l.png");
  ASSERT_EQ(l.pixels.size(), 60u);
  // Pixel (x, y) shows point (x, y): four grains, columns 0–2, 3–5, 6–8, 9–11, on every row.
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 12; ++x) {
      const int k = static_cast<int>(std::lround(l.pixels[y * 12 + x] * 65535.0f));
      EXPECT_EQ(k, 1 + x / 3) << x << "," << y;
    }
  const nlohmann::json g = nlohmann::json::parse(read_file(dir / "g.json"));
  ASSERT_EQ(g["grains"].size(), 4u);
  for (const auto& grain : g["grains"]) {
    EXPECT_EQ(grain["mineral"], "quartz");
    EXPECT_EQ(grain["area_px"], 15);
  }
  // The stats' model report says what the map became.
  const nlohmann::json st = nlohmann::json::parse(read_file(dir / "st.json"));
  const std::string report = st["model_report"];
  EXPECT_NE(report.find("EBSD map: 60 points (60 indexed), 4 grains"), std::string::npos) << report;
}

TEST(EbsdMapCli, ShippedExampleMapIsWhatTheGeneratorWrites) {
  ScratchDir dir;
  const std::string gen = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-ebsd-example";
  const CommandResult r = run_command({gen, "--out", dir / "q.ctf"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(read_file(dir / "q.ctf") == read_file(std::string(PMSIM_SOURCE_DIR) + "/assets/ebsd/quartzite_example.ctf"))
      << "assets/ebsd/quartzite_example.ctf differs from 'pmsim-ebsd-example --out quartzite_example.ctf': rerun it";
  // A bad extension is a usage error (exit 2) and writes nothing.
  const CommandResult bad = run_command({gen, "--out", dir / "q.txt"}, dir);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "q.txt"));
}

TEST(EbsdMapCli, ExampleSceneReportsGrainsAndFinerOrientationClusters) {
  ScratchDir dir;
  const CommandResult r = run_command(
      {kRender, std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/ebsd_map.json", "--set", "render.width=32", "--set",
       "render.height=32", "--set", "render.spp=1", "--set", "render.wavelengths=8", "--out", dir / "a.png",
       "--stats", dir / "st.json"},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = nlohmann::json::parse(read_file(dir / "st.json"))["model_report"];
  // "EBSD map: N points (M indexed), G grains (…), C orientation clusters": the subgrains and the
  // bending of the quartz grains make C several times G (each point within 0.5° of its cluster).
  const auto at = report.find("EBSD map: 10800 points");
  ASSERT_NE(at, std::string::npos) << report;
  const auto g_at = report.find("indexed), ", at) + 10;
  const long grains = std::stol(report.substr(g_at));
  const auto c_at = report.find("°), ", g_at) + std::string("°), ").size();
  const long clusters = std::stol(report.substr(c_at));
  EXPECT_GT(grains, 100);
  EXPECT_GT(clusters, 2 * grains) << report;
}
