// The shipped sections are exactly what their generator writes: running
// assets/sections/generate_sections.py again reproduces every file byte for byte (it is
// deterministic, and nobody edited its output by hand).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(SectionGenerator, RerunReproducesTheShippedFiles) {
  const fs::path src = fs::path(PMSIM_SOURCE_DIR) / "assets/sections";
  const fs::path out = fs::path(PMSIM_BINARY_DIR) / "section_generator_test_out";
  fs::remove_all(out);
  fs::create_directories(out);
  const std::string cmd = "python3 \"" + (src / "generate_sections.py").string() + "\" --out \"" + out.string() + "\"";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  int compared = 0;
  for (const auto& f : fs::directory_iterator(out)) {
    ASSERT_TRUE(fs::exists(src / f.path().filename())) << f.path().filename() << " is generated but not shipped";
    EXPECT_TRUE(bytes(f.path()) == bytes(src / f.path().filename()))
        << f.path().filename() << " differs from the generator's output: rerun generate_sections.py";
    ++compared;
  }
  EXPECT_GE(compared, 1);  // granite (basalt, gabbro and schist are grown from assets/rocks)
  fs::remove_all(out);
}
