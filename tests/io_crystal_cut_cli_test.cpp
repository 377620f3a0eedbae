// sample.cut through the scene reader and pmsim-render: bad cuts exit 2 naming the key, a cut
// survives save → load, and --set takes and clears it.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/base/input_error.h"
#include "core/io/scene_file.h"
#include "render_cli_run.h"

namespace fs = std::filesystem;
using namespace pmsim;

namespace {
const std::string kBinary = test::kRenderBinary;

std::string temp_dir() { return test::cli_temp_dir("cut_test"); }

using test::CliRun;
CliRun run(const std::string& args) { return test::run_render_cli(args, temp_dir()); }
const std::string kSmall = " --set render.width=8 --set render.height=8 --set render.spp=1 ";
}  // namespace

TEST(CrystalCutCli, BadCutsExitTwoNamingTheKey) {
  ASSERT_TRUE(fs::exists(kBinary)) << kBinary << " not built";
  const std::string out = temp_dir() + "/cut.png";
  // North out of the plane: [010] is the normal of (010) in a monoclinic cell, 90° off.
  CliRun r = run("--set sample.mineral=augite --set 'sample.cut={\"plane\":\"(010)\",\"north\":\"[010]\"}'" +
                 kSmall + "--out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("sample.cut.north"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("makes 90° with the plane (010)"), std::string::npos) << r.err;
  // A mineral without crystallographic data (triclinic plagioclase has none yet).
  r = run("--set sample.mineral=plagioclase --set 'sample.cut={\"plane\":\"(010)\",\"north\":\"[001]\"}'" +
          kSmall + "--out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'sample.cut'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("plagioclase"), std::string::npos) << r.err;
  // Malformed Miller text, and a cut with custom indices instead of a mineral.
  r = run("--set sample.mineral=augite --set 'sample.cut={\"plane\":\"(1x0)\",\"north\":\"[001]\"}'" +
          kSmall + "--out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'sample.cut'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(1x0)"), std::string::npos) << r.err;
  r =
      run("--set 'sample.crystal={\"no\":1.6,\"ne\":1.5}' --set "
          "'sample.cut={\"plane\":\"(010)\",\"north\":\"[001]\"}'" +
          kSmall + "--out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'sample.cut'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // The same from a scene file: the file is named too.
  const std::string scene = temp_dir() + "/cut_scene.json";
  std::ofstream(scene)
      << R"J({"sample": {"mineral": "hornblende", "cut": {"plane": "(110)", "north": "[100]"}}})J";
  r = run(scene + kSmall + "--out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(scene), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sample.cut.north"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // A good cut renders.
  r = run("--set sample.mineral=augite --set 'sample.cut={\"plane\":\"(010)\",\"north\":\"[001]\"}'" +
          kSmall + "--out " + out);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out));
}

TEST(CrystalCutScene, SurvivesSaveAndLoadAndSetClearsIt) {
  Scene s;
  s.sample.mineral = "augite";
  apply_setting(s, R"J(sample.cut={"plane":"(1-10)","north":"[001]"})J");
  ASSERT_TRUE(s.sample.cut);
  EXPECT_EQ(s.sample.cut->plane, "(1-10)");
  const Scene back = scene_from_json(scene_to_json(s), "saved.json");
  ASSERT_TRUE(back.sample.cut);
  EXPECT_EQ(back.sample.cut->plane, "(1-10)");
  EXPECT_EQ(back.sample.cut->north, "[001]");
  EXPECT_EQ(scene_to_json(back), scene_to_json(s));
  apply_setting(s, "sample.cut=none");
  EXPECT_FALSE(s.sample.cut);
  EXPECT_FALSE(scene_to_json(s)["sample"].contains("cut"));  // scenes without a cut unchanged
  // A refused --set leaves the scene as it was.
  Scene t = back;
  EXPECT_THROW(apply_setting(t, R"J(sample.cut={"plane":"(010)"})J"), InputError);
  EXPECT_EQ(t.sample.cut->plane, "(1-10)");
}
