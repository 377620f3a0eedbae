// Every scene of assets/scenes and assets/scenes3d rendered again with the built tools and compared
// with its golden image (tests/golden/, listed in manifest.txt, made by scripts/golden.sh). The
// renders are deterministic (fixed samples and bands, per-pixel sums in a fixed order), so a change
// that is not meant to change pixels must leave them as they were.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/image_file.h"

namespace fs = std::filesystem;

namespace {

const std::string kSource = PMSIM_SOURCE_DIR;
const std::string kBinary = PMSIM_BINARY_DIR;

struct GoldenCase {
  std::string name, tool, file;
  std::vector<std::string> settings;
};

// gtest prints a parameter in failure messages: its name, not its bytes.
void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.name; }

std::vector<GoldenCase> read_manifest() {
  std::vector<GoldenCase> cases;
  std::ifstream f(kSource + "/tests/golden/manifest.txt");
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream in(line);
    GoldenCase c;
    if (!(in >> c.name) || c.name[0] == '#') continue;
    in >> c.tool >> c.file;
    for (std::string s; in >> s;) c.settings.push_back(s);
    cases.push_back(c);
  }
  return cases;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }  // the manifest has no quotes

int run(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Renders one case into `dir`; returns the image path ("" when the tool failed).
std::string render(const GoldenCase& c, const fs::path& dir) {
  if (c.tool == "render") {
    std::string cmd = kBinary + "/app/pmsim-render " + quoted(kSource + "/assets/" + c.file);
    for (const std::string& s : c.settings) cmd += " --set " + quoted(s);
    const std::string out = (dir / (c.name + ".exr")).string();
    return run(cmd + " --out " + quoted(out)) == 0 ? out : "";
  }
  if (c.tool == "vignetting") {
    const fs::path out_dir = dir / c.name;
    const std::string cmd =
        kBinary + "/app/pmsim-experiments --quick --out-dir " + quoted(out_dir.string()) + " vignetting";
    return run(cmd) == 0 ? (out_dir / "vignetting_zones.png").string() : "";
  }
  return "";
}

class GoldenImage : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(GoldenImage, RenderMatchesGolden) {
  const GoldenCase& c = GetParam();
  const fs::path dir =
      fs::temp_directory_path() / ("pmsim_golden_" + std::to_string(::getpid()) + "_" + c.name);
  fs::create_directories(dir);
  const std::string path = render(c, dir);
  ASSERT_FALSE(path.empty()) << c.name << ": the " << c.tool << " tool failed";
  const bool png = c.tool == "vignetting";
  const pmsim::LoadedImage golden =
      pmsim::read_image(kSource + "/tests/golden/" + c.name + (png ? ".png" : ".exr"));
  const pmsim::LoadedImage now = pmsim::read_image(path);
  fs::remove_all(dir);
  ASSERT_EQ(now.width, golden.width);
  ASSERT_EQ(now.height, golden.height);
  ASSERT_EQ(now.channels, golden.channels);
  ASSERT_EQ(now.pixels.size(), golden.pixels.size());
  double max_diff = 0.0;
  std::size_t worst = 0;
  for (std::size_t i = 0; i < now.pixels.size(); ++i) {
    ASSERT_TRUE(std::isfinite(now.pixels[i])) << c.name << ": sample " << i;
    const double d = std::fabs(static_cast<double>(now.pixels[i]) - golden.pixels[i]);
    if (d > max_diff) max_diff = d, worst = i;
  }
  // The same build reproduces the golden images bit for bit (measured: 0). Another compiler (the
  // clang sanitizer build) may round a few operations differently: 2e-6 of linear RGB (white = 1)
  // is ~10 float ulps at 1 and a fifth of one 16-bit level, far below a visible change (ΔE00 0.1
  // in a mid grey is ~1e-3). An 8-bit PNG may flip one level where a value sits on a rounding edge.
  const double budget = png ? 1.0 / 255.0 + 1e-6 : 2e-6;
  EXPECT_LE(max_diff, budget) << c.name << ": largest difference at sample " << worst << " (pixel "
                              << worst / now.channels << ", channel " << worst % now.channels << ")";
  RecordProperty("max_abs_difference", std::to_string(max_diff));
}

INSTANTIATE_TEST_SUITE_P(Scenes, GoldenImage, ::testing::ValuesIn(read_manifest()),
                         [](const ::testing::TestParamInfo<GoldenCase>& i) { return i.param.name; });

TEST(GoldenManifest, CoversEverySceneFile) {
  // Every scene shipped in assets/scenes and assets/scenes3d has a golden line, so that a new
  // scene cannot escape the guard.
  std::vector<std::string> listed;
  for (const GoldenCase& c : read_manifest()) listed.push_back(c.file);
  for (const char* sub : {"scenes", "scenes3d"})
    for (const auto& e : fs::directory_iterator(kSource + "/assets/" + sub))
      if (e.path().extension() == ".json") {
        const std::string rel = std::string(sub) + "/" + e.path().filename().string();
        EXPECT_NE(std::find(listed.begin(), listed.end(), rel), listed.end())
            << rel << " has no golden image";
      }
}

}  // namespace
