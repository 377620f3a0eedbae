// The command-line policy every executable shares (core/io/cli_policy.h), through the built binaries:
// --help and -h print the usage with every option on stdout and exit 0; a usage error prints
// "<program>: <what is wrong>" and the pointer to --help on stderr, nothing on stdout, and exits
// 2; a repeated --set keeps every value in command-line order (the last one wins).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/io/image_file.h"
#include "tests/reliability_support.h"

namespace pmsim {
namespace {

using reliability::CommandResult;
using reliability::run_command;
using reliability::ScratchDir;
namespace fs = std::filesystem;

const std::string kApp = std::string(PMSIM_BINARY_DIR) + "/app/";

struct Program {
  std::string name;
  std::vector<std::string> options;  // every option the program documents
};

// The app (pmsim) exists only in builds with the UI (the sanitizer tree builds without it).
const Program kPrograms[] = {
#if PMSIM_WITH_UI
    {"pmsim",
     {"--headless", "--set", "--frames", "--script", "--screenshot", "--no-settle", "--timeout", "--size",
      "--threads", "--report-fps"}},
#endif
    {"pmsim-render", {"--set", "--out", "--stats"}},
    {"pmsim-trace",
     {"--lens", "--origin", "--dir", "--pol", "--wavelength-nm", "--intensity", "--source", "--delta-rad",
      "--optical-path-mm", "--depth", "--tir", "--ledge"}},
    {"pmsim-bench",
     {"--quick", "--json", "--out-dir", "--size", "--threads", "--cache-dir", "--no-throughput", "--scene",
      "--strategy", "--images", "--from-json", "--apply-settings", "--rocks"}},
    {"pmsim-experiments", {"--out-dir", "--quick", "fig3", "fig4", "brewster", "vignetting", "cone-table"}},
    {"pmsim-exercise", {"make", "grade", "list"}},
};

// The one message style of a usage error.
void expect_usage_error(const CommandResult& r, const std::string& program, const std::string& named) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out, "") << "a usage error prints nothing on stdout";
  EXPECT_EQ(r.err.rfind(program + ": ", 0), 0u) << "stderr must start with '" << program << ": ': " << r.err;
  EXPECT_NE(r.err.find(named), std::string::npos) << "stderr does not name '" << named << "': " << r.err;
  EXPECT_NE(r.err.find("Run '" + program + " --help' for usage."), std::string::npos) << r.err;
}

class CliHelp : public ::testing::Test {
 protected:
  ScratchDir dir_;
};

TEST_F(CliHelp, HelpPrintsEveryOptionAndExitsZero) {
  for (const Program& p : kPrograms) {
    SCOPED_TRACE(p.name);
    if (!fs::exists(kApp + p.name)) {
      ADD_FAILURE() << p.name << " not built";
      continue;
    }
    const CommandResult help = run_command({kApp + p.name, "--help"}, dir_);
    EXPECT_EQ(help.exit_code, 0) << help.err;
    EXPECT_EQ(help.err, "");
    EXPECT_NE(help.out.find("Usage: " + p.name), std::string::npos) << help.out;
    for (const std::string& o : p.options)
      EXPECT_NE(help.out.find(o), std::string::npos) << o << " missing:\n" << help.out;
    const CommandResult h = run_command({kApp + p.name, "-h"}, dir_);
    EXPECT_EQ(h.exit_code, 0) << h.err;
    EXPECT_EQ(h.out, help.out);
  }
}

TEST_F(CliHelp, UnknownOptionsAreOneStyleOfUsageErrorWithExitTwo) {
  for (const Program& p : kPrograms) {
    SCOPED_TRACE(p.name);
    if (!fs::exists(kApp + p.name)) continue;  // reported by the test above
    expect_usage_error(run_command({kApp + p.name, "--no-such-option"}, dir_), p.name, "--no-such-option");
  }
}

TEST_F(CliHelp, ValueErrorsFoundAfterParsingHaveTheSameStyle) {
  // One per program: a value the parser takes as text and the program then refuses, or a
  // missing required option.
  if (PMSIM_WITH_UI) {
    expect_usage_error(run_command({kApp + "pmsim", "--headless", "--frames", "many", "--report-fps"}, dir_),
                       "pmsim", "--frames many");
    expect_usage_error(run_command({kApp + "pmsim", "--headless"}, dir_), "pmsim", "--screenshot");
    expect_usage_error(run_command({kApp + "pmsim", "--size", "640"}, dir_), "pmsim", "--size 640");
  }
  expect_usage_error(run_command({kApp + "pmsim-render", "--out", dir_ / "x.bmp"}, dir_), "pmsim-render",
                     "x.bmp");
  expect_usage_error(run_command({kApp + "pmsim-render"}, dir_), "pmsim-render", "--out");
  // Unexpected arguments in command-line order, and before a missing required option.
  expect_usage_error(
      run_command({kApp + "pmsim-render", "a.json", "b.json", "c.json", "--out", dir_ / "x.png"}, dir_),
      "pmsim-render", "not expected: b.json c.json");
  expect_usage_error(run_command({kApp + "pmsim-trace", "--lense", "a.json"}, dir_), "pmsim-trace",
                     "not expected: --lense a.json");
  expect_usage_error(run_command({kApp + "pmsim-trace", "--origin", "0,0,-10"}, dir_), "pmsim-trace",
                     "--lens");
  expect_usage_error(run_command({kApp + "pmsim-trace", "--lens", "a.json", "--lens", "b.json"}, dir_),
                     "pmsim-trace", "--lens");
  expect_usage_error(run_command({kApp + "pmsim-bench", "--size", "banana"}, dir_), "pmsim-bench", "banana");
  expect_usage_error(run_command({kApp + "pmsim-bench", "--threads", "-1"}, dir_), "pmsim-bench",
                     "--threads");
  expect_usage_error(run_command({kApp + "pmsim-experiments"}, dir_), "pmsim-experiments", "subcommand");
}

TEST_F(CliHelp, RepeatedSetKeepsItsOrderAndAnOptionGivenTwiceKeepsTheLast) {
  if (!fs::exists(kApp + "pmsim-render")) GTEST_SKIP() << "pmsim-render not built";
  // The scene file may stand between the --set options; the later stage_deg wins, as with the
  // hand-written parser; so does the later --out.
  const std::string scene = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/quartz_section_ortho.json";
  const CommandResult r =
      run_command({kApp + "pmsim-render", "--set", "stage_deg=10", scene, "--set=stage_deg=20", "--set",
                   "render.width=8", "--set", "render.height=8", "--set", "render.spp=1", "--set",
                   "render.wavelengths=4", "--out", dir_ / "first.exr", "-o", dir_ / "out.exr"},
                  dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "first.exr"));
  const LoadedImage img = read_image(dir_ / "out.exr");
  ASSERT_TRUE(img.metadata.contains("pmsim:scene"));
  EXPECT_EQ(img.metadata["pmsim:scene"]["stage_deg"].get<double>(), 20.0);  // exact: a typed integer
  EXPECT_EQ(img.metadata["pmsim:scene"]["render"]["width"].get<int>(), 8);
}

}  // namespace
}  // namespace pmsim
