// Bad input on the command line, through the built binaries (PMSIM_BINARY_DIR/app): pmsim-trace
// and pmsim-render must answer every bad argument, scene or lens with exit code 2 and a message
// naming the file/key/value; pmsim-trace prints nothing on stdout then, and pmsim-render leaves no
// output file (nor temporary) behind and an existing one untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/reliability_support.h"

namespace pmsim {
namespace {

using reliability::CommandResult;
using reliability::run_command;
using reliability::ScratchDir;
namespace fs = std::filesystem;

const std::string kApp = std::string(PMSIM_BINARY_DIR) + "/app/";
const std::string kAssets = std::string(PMSIM_SOURCE_DIR) + "/assets/";

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class TraceCli : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kApp + "pmsim-trace")) GTEST_SKIP() << "pmsim-trace not built";
  }
  // The documented example ray with `key` replaced by `value` (or added).
  CommandResult trace(const std::vector<std::pair<std::string, std::string>>& changes,
                      const std::string& lens = kAssets + "lenses/biconvex_bk7.json") {
    std::vector<std::pair<std::string, std::string>> a = {{"--lens", lens},
                                                          {"--origin", "0,0,-10"},
                                                          {"--dir", "0,0,1"},
                                                          {"--pol", "1,0,0"},
                                                          {"--wavelength-nm", "550"}};
    for (const auto& change : changes) {  // (no structured binding: clang 14 cannot capture one)
      const std::string& k = change.first;
      const std::string& v = change.second;
      auto it = std::find_if(a.begin(), a.end(), [&](const auto& p) { return p.first == k; });
      if (it != a.end()) {
        if (v == "<drop>")
          a.erase(it);
        else
          it->second = v;
      } else {
        a.push_back({k, v});
      }
    }
    std::vector<std::string> argv = {kApp + "pmsim-trace"};
    for (const auto& [k, v] : a) {
      argv.push_back(k);
      argv.push_back(v);
    }
    return run_command(argv, dir_);
  }
  void expect_bad(const std::vector<std::pair<std::string, std::string>>& changes, const std::string& key,
                  const std::string& value, const std::string& lens = kAssets + "lenses/biconvex_bk7.json") {
    std::string what;
    for (const auto& [k, v] : changes) what += k + " " + v + " ";
    SCOPED_TRACE(what);
    const CommandResult r = trace(changes, lens);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.out, "") << "bad input must print nothing on stdout";
    EXPECT_NE(r.err.find(key), std::string::npos) << "stderr does not name '" << key << "': " << r.err;
    EXPECT_NE(r.err.find(value), std::string::npos) << "stderr does not show '" << value << "': " << r.err;
  }
  ScratchDir dir_;
};

TEST_F(TraceCli, TheDocumentedExampleTraces) {
  const CommandResult r = trace({});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["rays"].empty());
}

TEST_F(TraceCli, NonUnitVectorsAreNormalised) {
  // --dir and --pol are directions: any positive length means the same ray.
  const CommandResult a = trace({});
  const CommandResult b = trace({{"--dir", "0,0,7"}, {"--pol", "0.001,0,0"}});
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(a.out, b.out);
}

TEST_F(TraceCli, BadVectorsAndNumbersExitTwoNamingTheOption) {
  expect_bad({{"--dir", "0,0,0"}}, "--dir", "0,0,0");
  expect_bad({{"--pol", "0,0,0"}}, "--pol", "0,0,0");
  expect_bad({{"--pol", "0,0,1"}}, "--pol", "0,0,1");      // along dir
  expect_bad({{"--pol", "1,0,0.1"}}, "--pol", "1,0,0.1");  // not perpendicular
  expect_bad({{"--dir", "0,0"}}, "--dir", "0,0");
  expect_bad({{"--origin", "nan,0,0"}}, "--origin", "nan");
  expect_bad({{"--origin", "0,inf,0"}}, "--origin", "inf");
  expect_bad({{"--wavelength-nm", "nan"}}, "--wavelength-nm", "nan");
  expect_bad({{"--wavelength-nm", "-550"}}, "--wavelength-nm", "-550");
  expect_bad({{"--wavelength-nm", "abc"}}, "--wavelength-nm", "abc");
  expect_bad({{"--intensity", "-1"}}, "--intensity", "-1");
  expect_bad({{"--depth", "1000000"}}, "--depth", "1000000");  // dT 10⁶
  expect_bad({{"--depth", "-1"}}, "--depth", "-1");
  expect_bad({{"--depth", "2.5"}}, "--depth", "2.5");
  expect_bad({{"--tir", "bounce"}}, "--tir", "bounce");
  expect_bad({{"--source", "99999999999999"}}, "--source", "99999999999999");
  expect_bad({{"--bogus", "1"}}, "--bogus", "1");
  expect_bad({{"--pol", "<drop>"}}, "--pol", "");
}

TEST_F(TraceCli, WavelengthsOutsideTheGlassDataExitTwo) {
  // N-BK7's Sellmeier data hold for 310–2500 nm; Medium::n throws std::out_of_range outside, which
  // pmsim-trace reported with exit code 1 (not an InputError). Finding F3.
  expect_bad({{"--wavelength-nm", "200"}}, "--wavelength-nm", "200");
  expect_bad({{"--wavelength-nm", "1e6"}}, "--wavelength-nm", "1e6");
}

TEST_F(TraceCli, BadLensFilesExitTwoNamingFileKeyAndValue) {
  expect_bad({}, "missing.json", "", dir_ / "missing.json");
  const std::string zero = dir_.file("zero.json", R"({"glass":"N-BK7","radius_mm":0,"ledge_mm":1})");
  expect_bad({}, "radius_mm", "0", zero);
  const std::string glass = dir_.file("glass.json", R"({"glass":"unobtainium","radius_mm":2,"ledge_mm":1})");
  expect_bad({}, "unobtainium", "glass", glass);
  const std::string trunc = dir_.file("trunc.json", R"({"glass":"N-BK7","radius_mm":2,"led)");
  expect_bad({}, "trunc.json", "", trunc);
  const std::string latin1 =
      dir_.file("latin1.json", "{\"glass\":\"N-BK7\xe4\",\"radius_mm\":2,\"ledge_mm\":1}");
  expect_bad({}, "latin1.json", "", latin1);
  const std::string typo =
      dir_.file("typo.json", R"({"glass":"N-BK7","radius_mm":2,"ledge_mm":1,"centre":[0,0,0]})");
  expect_bad({}, "centre", "", typo);
}

TEST_F(TraceCli, AbsurdButFiniteRaysNeverPrintNaN) {
  // An origin 10³⁰⁰ mm away is finite, so it is legal input; the answer must still be finite.
  for (const char* origin : {"1e300,0,-1e300", "0,0,-1e-300", "4.25,0,-10", "0,4.2499999999,-10"}) {
    SCOPED_TRACE(origin);
    const CommandResult r = trace({{"--origin", origin}, {"--depth", "64"}, {"--tir", "split"}});
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.exit_code << " " << r.err;
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("inf"), std::string::npos) << r.out;
  }
}

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kApp + "pmsim-render")) GTEST_SKIP() << "pmsim-render not built";
    old_ = dir_.file("old.png", "previous image");
  }
  // A tiny render so that accepted inputs finish at once.
  CommandResult render(std::vector<std::string> args, const std::string& out_name = "out.png") {
    std::vector<std::string> argv = {kApp + "pmsim-render"};
    argv.insert(argv.end(), args.begin(), args.end());
    for (const char* s : {"render.width=8", "render.height=8", "render.spp=1", "render.wavelengths=4"}) {
      if (std::find(args.begin(), args.end(), std::string("--no-small")) != args.end()) break;
      argv.push_back("--set");
      argv.push_back(s);
    }
    argv.erase(std::remove(argv.begin(), argv.end(), std::string("--no-small")), argv.end());
    argv.push_back("--out");
    argv.push_back(dir_ / out_name);
    return run_command(argv, dir_);
  }
  void expect_bad(const std::vector<std::string>& args, const std::vector<std::string>& named,
                  const std::string& out_name = "out.png") {
    std::string what;
    for (const auto& a : args) what += a + " ";
    SCOPED_TRACE(what);
    const auto before = listing(dir_.path());
    const CommandResult r = render(args, out_name);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    for (const std::string& n : named) {  // "a|b": either spelling (numbers may be reformatted)
      bool found = false;
      std::stringstream alts(n);
      for (std::string alt; std::getline(alts, alt, '|');) found |= r.err.find(alt) != std::string::npos;
      EXPECT_TRUE(found) << "stderr does not name '" << n << "': " << r.err;
    }
    EXPECT_EQ(listing(dir_.path()), before) << "an output or temporary file was left behind";
    EXPECT_EQ(reliability::read_file(old_), "previous image");
  }
  ScratchDir dir_;
  std::string old_;
};

TEST_F(RenderCli, BadScenesExitTwoNamingFileKeyAndValueAndWriteNothing) {
  const std::string neg = dir_.file("neg.json", R"({"sample":{"thickness_um":-5}})");
  expect_bad({neg}, {"neg.json", "sample.thickness_um", "-5"});
  const std::string na = dir_.file("na.json", R"({"objective":{"na":1.3}})");
  expect_bad({na}, {"na.json", "objective.na", "1.3"});
  const std::string trunc = dir_.file("trunc.json", R"({"sample":{"thickness_um":)");
  expect_bad({trunc}, {"trunc.json"});
  const std::string latin1 = dir_.file("latin1.json", "{\"sample\":{\"mineral\":\"qu\xe4rtz\"}}");
  expect_bad({latin1}, {"latin1.json"});
  const std::string big = dir_.file("big.json", R"({"stage_deg":1e400})");
  expect_bad({big}, {"big.json"});
  const std::string mineral = dir_.file("mineral.json", R"({"sample":{"mineral":"unobtainium"}})");
  expect_bad({mineral}, {"mineral.json", "sample.mineral", "unobtainium"});
  expect_bad({dir_ / "missing.json"}, {"missing.json"});
  fs::remove(neg);
  fs::remove(na);
  fs::remove(trunc);
  fs::remove(latin1);
  fs::remove(big);
  fs::remove(mineral);
}

TEST_F(RenderCli, BadSetValuesExitTwoNamingKeyAndValue) {
  expect_bad({"--set", "objective.na=1.2"}, {"objective.na", "1.2"});
  expect_bad({"--set", "sample.thickness_um=0"}, {"sample.thickness_um", "0"});
  expect_bad({"--set", "render.single_wavelength_nm=900"}, {"render.single_wavelength_nm", "900"});
  expect_bad({"--set", "sample.optic_axis=[0,0,0]"}, {"sample.optic_axis"});
  expect_bad({"--set", "stage_deg=nan"}, {"stage_deg", "nan"});
  expect_bad({"--set", "optics.lens_depth=1000000"}, {"optics.lens_depth", "1000000|1e+06"});
  expect_bad({"--set", "sample.type=plate", "--set", "sample.mineral=unobtainium"},
             {"sample.mineral", "unobtainium"});
  expect_bad({"--set", "nosuchkey=1"}, {"nosuchkey"});
  expect_bad({"--set", "stage_deg"}, {"stage_deg"});
  expect_bad({"--bogus"}, {"--bogus"});
  expect_bad({}, {"out.xyz"}, "out.xyz");
}

TEST_F(RenderCli, ParallelBiaxialAxesExitTwoInsteadOfAborting) {
  // x_axis ∥ z_axis passed validation; biaxial_orientation then threw std::invalid_argument,
  // which nothing caught: pmsim-render aborted (exit 134). Finding F7.
  const std::string par = dir_.file(
      "par.json", R"({"sample":{"type":"plate","mineral":"muscovite","x_axis":[0,0,1],"z_axis":[0,0,2]}})");
  expect_bad({par}, {"par.json", "sample.x_axis|sample.z_axis"});
  fs::remove(par);
}

TEST_F(RenderCli, PerpendicularAxesSetTogetherRenderInEitherOrder) {
  // Every --set was validated against the half-changed scene, so turning the biaxial frame
  // (each new axis parallel to the other's old value) failed whatever the order.
  for (const auto& [first, second] : {std::pair{"sample.x_axis=[0,0,1]", "sample.z_axis=[1,0,0]"},
                                      std::pair{"sample.z_axis=[1,0,0]", "sample.x_axis=[0,0,1]"}}) {
    SCOPED_TRACE(first);
    const CommandResult r = render({"--set", "sample.mineral=muscovite", "--set", first, "--set", second});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
    fs::remove(dir_ / "out.png");
  }
}

TEST_F(RenderCli, AFileAndSetObeyTheSameRules) {
  // A sample of the wrong type was warned as an unknown key and rendered; oblique biaxial axes
  // rendered from a file although the same values are refused on the command line.
  const std::string str = dir_.file("str.json", R"({"sample":"quartz"})");
  expect_bad({str}, {"str.json", "sample", "quartz"});
  const std::string oblique =
      dir_.file("oblique.json", R"({"sample":{"mineral":"muscovite","x_axis":[1,0,0.5],"z_axis":[0,0,1]}})");
  expect_bad({oblique}, {"oblique.json", "sample.x_axis", "[1,0,0.5]"});
  expect_bad({"--set", "sample.mineral=muscovite", "--set", "sample.x_axis=[1,0,0.5]"},
             {"command line", "sample.x_axis", "[1,0,0.5]"});
  fs::remove(str);
  fs::remove(oblique);
}

TEST_F(RenderCli, HugeImagesAreRefusedBeforeAnyAllocation) {
  // 100 000² pixels would need ~10¹¹ bytes; it must be a clean exit 2, not an OOM kill.
  expect_bad({"--no-small", "--set", "render.width=100000", "--set", "render.height=100000"},
             {"render.width", "100000"});
}

TEST_F(RenderCli, UnknownSceneKeysAreWarningsNamingTheKey) {
  const std::string typo = dir_.file("typo.json", R"({"stgae_deg":45})");
  const CommandResult r = render({typo});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("stgae_deg"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out.png"));
}

TEST_F(RenderCli, AnUnwritableOutputFolderFailsCleanly) {
  // A path below a regular file cannot be created even by root (ENOTDIR).
  const CommandResult r = render({}, "old.png/out.png");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("old.png/out.png"), std::string::npos) << r.err;
  EXPECT_EQ(reliability::read_file(old_), "previous image");
}

}  // namespace
}  // namespace pmsim
