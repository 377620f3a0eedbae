// pmsim-experiments as a user meets it: bad input exits with code 2 and writes nothing; a run
// prints the paper's tables next to ours.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

const std::string kExe = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-experiments";

int run(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ExperimentsCli, BadSceneExitsWithCode2AndWritesNoImage) {
  if (!fs::exists(kExe)) GTEST_SKIP() << "pmsim-experiments not built";
  const fs::path dir = fs::temp_directory_path() / ("pmsim_exp_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir / "scenes3d");
  std::ifstream in(std::string(PMSIM_SOURCE_DIR) + "/assets/scenes3d/fig3_lens_point_light.json");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string key = "\"fov_deg\"";
  text.replace(text.find(key), key.size(), "\"fov\"");  // a typo a user could make
  std::ofstream(dir / "scenes3d" / "fig3_lens_point_light.json") << text;
  const std::string cmd = "PMSIM_ASSETS=" + dir.string() + " " + kExe + " fig3 --quick --out-dir " +
                          (dir / "out").string() + " > " + (dir / "log.txt").string() + " 2>&1";
  EXPECT_EQ(run(cmd), 2);
  std::ifstream log(dir / "log.txt");
  std::stringstream ls;
  ls << log.rdbuf();
  EXPECT_NE(ls.str().find("camera.fov"), std::string::npos) << ls.str();
  EXPECT_FALSE(fs::exists(dir / "out" / "fig3a_rgb.png"));
  fs::remove_all(dir);
}

TEST(ExperimentsCli, ConeTablePrintsOursNextToThePapers) {
  if (!fs::exists(kExe)) GTEST_SKIP() << "pmsim-experiments not built";
  const fs::path log = fs::temp_directory_path() / ("pmsim_cone_" + std::to_string(::getpid()));
  ASSERT_EQ(run(kExe + " cone-table --quick > " + log.string()), 0);
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string out = ss.str();
  EXPECT_NE(out.find("Table 1"), std::string::npos);
  EXPECT_NE(out.find("Table 2"), std::string::npos);
  EXPECT_NE(out.find("0.00744892"), std::string::npos);  // the paper's η4 for the 20 % cone
  EXPECT_NE(out.find("Sensitivity"), std::string::npos);
  fs::remove(log);
}

}  // namespace
