// The pmsim-trace contract (issue #2): run the built binary, check its JSON against the library
// bit for bit, the energy sum, and bad input (message naming the key, exit 2, empty stdout).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/lens/lens_tracer.h"

using namespace pmsim;
namespace fs = std::filesystem;

namespace {
const std::string kBin = std::string(PMSIM_BINARY_DIR) + "/app/pmsim-trace";
const std::string kLens = std::string(PMSIM_SOURCE_DIR) + "/assets/lenses/biconvex_bk7.json";

struct CliResult {
  int code;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

CliResult run(const std::string& args) {
  const fs::path dir = fs::temp_directory_path() / ("pmsim_trace_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string cmd =
      "'" + kBin + "' " + args + " >'" + (dir / "out").string() + "' 2>'" + (dir / "err").string() + "'";
  const int status = std::system(cmd.c_str());
  CliResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "out"), slurp(dir / "err")};
  fs::remove_all(dir);
  return r;
}

fs::path write_lens(const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("pmsim_lens_" + std::to_string(::getpid()) + ".json");
  std::ofstream(p) << text;
  return p;
}

const char* kRay = " --origin 1.5,0.25,-10 --dir 0.05,0,1 --pol 0,1,0 --wavelength-nm 546.1";
}  // namespace

TEST(PmsimTraceCli, OutputMatchesTheLibraryToTheLastBitAndBalancesEnergy) {
  ASSERT_TRUE(fs::exists(kBin)) << "build the pmsim-trace target first: " << kBin;
  const CliResult r =
      run("--lens '" + kLens + "'" + kRay +
          " --intensity 2 --source 7 --delta-rad 0.5 --optical-path-mm 3 --depth 4 --tir split");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);

  PolarizedRay in;
  in.origin = {1.5, 0.25, -10};
  in.dir = glm::normalize(glm::dvec3(0.05, 0, 1));
  in.pol = {0, 1, 0};
  in.wavelength_nm = 546.1;
  in.intensity = 2;
  in.source = 7;
  in.delta_rad = 0.5;
  in.optical_path_mm = 3;
  LensTraceOptions opt;
  opt.max_depth = 4;
  opt.tir = TirMode::Split;
  const LensBundle b = trace_lens(Lens(load_lens_spec(kLens)), in, opt);

  // 17 significant digits round-trip doubles exactly: compare with ==.
  ASSERT_EQ(j["rays"].size(), b.rays.size());
  double sum = 0;
  for (size_t i = 0; i < b.rays.size(); ++i) {
    const auto& jr = j["rays"][i];
    const PolarizedRay& ray = b.rays[i];
    EXPECT_EQ(jr["intensity"].get<double>(), ray.intensity);
    EXPECT_EQ(jr["optical_path_mm"].get<double>(), ray.optical_path_mm);
    EXPECT_EQ(jr["delta_rad"].get<double>(), ray.delta_rad);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(jr["origin"][c].get<double>(), ray.origin[c]);
      EXPECT_EQ(jr["dir"][c].get<double>(), ray.dir[c]);
      EXPECT_EQ(jr["pol"][c].get<double>(), ray.pol[c]);
    }
    EXPECT_EQ(jr["depth"].get<int>(), ray.depth);
    EXPECT_EQ(jr["source"].get<int>(), 7);
    EXPECT_EQ(jr["wavelength_nm"].get<double>(), 546.1);
    EXPECT_GE(jr["optical_path_mm"].get<double>(), 3.0);  // input O_p + n·S
    sum += jr["intensity"].get<double>();
  }
  for (const auto& e : j["events"]) sum += e["intensity"].get<double>();
  sum += j["absorbed"].get<double>();
  EXPECT_NEAR(sum, 2.0, 2e-12);  // the contract's 1e-12 relative
  EXPECT_EQ(j["events"].size(), b.events.size());
  EXPECT_EQ(r.err, "");
}

TEST(PmsimTraceCli, MissingTheLensGivesOneMissEvent) {
  ASSERT_TRUE(fs::exists(kBin));
  const CliResult r =
      run("--lens '" + kLens + "' --origin 30,0,-10 --dir 0,0,1 --pol 1,0,0 --wavelength-nm 550");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["rays"].empty());
  ASSERT_EQ(j["events"].size(), 1u);
  EXPECT_EQ(j["events"][0]["type"], "miss");
  EXPECT_EQ(j["events"][0]["intensity"].get<double>(), 1.0);
}

TEST(PmsimTraceCli, BadInputNamesTheKeyExitsTwoAndWritesNothing) {
  ASSERT_TRUE(fs::exists(kBin));
  struct Case {
    std::string args, key;
  };
  const std::string good_lens = "--lens '" + kLens + "'";
  const fs::path bad_radius =
      write_lens(R"({"glass":"N-BK7","radius_mm":4.25,"front":{"radius_mm":3},"ledge_mm":0.3})");
  const fs::path bad_glass = fs::path(bad_radius).replace_extension(".g.json");
  std::ofstream(bad_glass)
      << R"({"glass":"unobtainium","radius_mm":4.25,"front":{"radius_mm":8},"ledge_mm":0.3})";
  const fs::path disagree = fs::path(bad_radius).replace_extension(".t.json");
  std::ofstream(disagree)
      << R"({"glass":"N-BK7","radius_mm":4.25,"front":{"radius_mm":8},"ledge_mm":0.3,"thickness_mm":1})";
  const Case cases[] = {
      {good_lens + " --origin 0,0,-10 --dir 0,0,1 --pol 1,0,0.01 --wavelength-nm 550", "--pol"},
      {good_lens + " --origin 0,0,-10 --dir 0,0,0 --pol 1,0,0 --wavelength-nm 550", "--dir"},
      {good_lens + " --origin 0,0 --dir 0,0,1 --pol 1,0,0 --wavelength-nm 550", "--origin"},
      {good_lens + " --origin 0,0,-10 --dir 0,0,1 --pol 1,0,0", "--wavelength-nm"},
      {good_lens + kRay + " --tir bounce", "--tir"},
      {good_lens + kRay + " --depth -1", "--depth"},
      {good_lens + kRay + " --ledge callback", "--ledge"},
      {"--lens '" + bad_radius.string() + "'" + kRay, "front.radius_mm"},
      {"--lens '" + bad_glass.string() + "'" + kRay, "glass"},
      {"--lens '" + disagree.string() + "'" + kRay, "ledge_mm"},
      {"--lens /nonexistent/lens.json" + std::string(kRay), "/nonexistent/lens.json"},
      // The model covers 380–780 nm; 200 nm is also outside N-BK7's Sellmeier data.
      {good_lens + " --origin 0,0,-10 --dir 0,0,1 --pol 1,0,0 --wavelength-nm 200", "--wavelength-nm"},
      {good_lens + " --origin 0,0,-10 --dir 0,0,1 --pol 1,0,0 --wavelength-nm 781", "--wavelength-nm"},
      {"--lens /tmp" + std::string(kRay), "/tmp"},  // a folder given as the lens file
  };
  for (const Case& c : cases) {
    const CliResult r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_EQ(r.out, "") << c.args;
    EXPECT_NE(r.err.find(c.key), std::string::npos) << c.args << " → " << r.err;
  }
  fs::remove(bad_radius);
  fs::remove(bad_glass);
  fs::remove(disagree);
}
