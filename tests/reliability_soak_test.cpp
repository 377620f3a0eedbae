// The short soak that ctest always runs: the headless app (when the UI is built) through
// scripts/soak.sh's random walk of 300 frames, including invalid values that must raise the error
// banner and keep the last good scene. The long soak (10 000 frames, 100 000 renderer restarts)
// is `scripts/soak.sh`, or this test with PMSIM_LONG_TESTS=1.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "tests/reliability_support.h"

namespace pmsim {
namespace {

TEST(Soak, HeadlessAppRandomWalkOfControls) {
  const std::string app = std::string(PMSIM_BINARY_DIR) + "/app/pmsim";
  if (!std::filesystem::exists(app)) GTEST_SKIP() << "the app is not built (PMSIM_BUILD_UI=OFF)";
  const char* long_env = std::getenv("PMSIM_LONG_TESTS");
  const bool is_long = long_env && std::string(long_env) == "1";
  reliability::ScratchDir dir;
  const auto r = reliability::run_command(
      {"/bin/bash", std::string(PMSIM_SOURCE_DIR) + "/scripts/soak.sh", "--build", PMSIM_BINARY_DIR,
       "--frames", is_long ? "10000" : "300", "--restarts", is_long ? "100000" : "0"},
      dir);
  std::cout << r.out;
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("exit 0, frames drawn"), std::string::npos) << r.out << r.err;
}

}  // namespace
}  // namespace pmsim
