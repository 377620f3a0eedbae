// pmsim-ebsd-example: writes the made-up EBSD map of core/ebsd/example_map.h (a calcite-bearing
// quartzite with subgrains, undulose bending, e-twinned calcite and non-indexed boundary points)
// as an Oxford .ctf or EDAX .ang file, for the example scene assets/scenes/ebsd_map.json and for
// trying maps without a microscope's data.
#include <filesystem>
#include <iostream>
#include <string>

#include "core/io/cli_policy.h"
#include "core/ebsd/example_map.h"
#include "core/ebsd/map_writer.h"
#include "core/ebsd/read_orientation_map.h"

namespace {
constexpr const char* kProgram = "pmsim-ebsd-example";
}

int main(int argc, char** argv) {
  CLI::App app{"Writes a made-up EBSD orientation map (calcite-bearing quartzite) as .ctf or .ang", kProgram};
  std::string out;
  int columns = 120, rows = 90;
  double step_um = 20.0, grain_um = 300.0;
  unsigned long long seed = 1;
  app.add_option("--out", out, "the map file to write (.ctf: Oxford Channel 5, .ang: EDAX/TSL)")->required();
  app.add_option("--columns", columns, "points per row")->check(CLI::Range(1, 100000));
  app.add_option("--rows", rows, "rows")->check(CLI::Range(1, 100000));
  app.add_option("--step_um", step_um, "distance between points (µm)")->check(CLI::PositiveNumber);
  app.add_option("--grain_um", grain_um, "mean grain size (µm)")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "random seed (the same seed, the same map)");
  pmsim::cli::parse_or_exit(app, argc, argv);
  if (!pmsim::is_orientation_map_path(out)) pmsim::cli::usage_error(kProgram, "--out must end in .ctf or .ang: '" + out + "'");
  try {
    const pmsim::OrientationMap m = pmsim::example_quartzite_map(columns, rows, step_um, grain_um, seed);
    // Written beside the target and renamed: never a half-written map under its name.
    const std::string ext = std::filesystem::path(out).extension().string();
    const std::string tmp = out + ".tmp" + ext;
    if (ext == ".ang" || ext == ".ANG")
      pmsim::write_ang(m, tmp);
    else
      pmsim::write_ctf(m, tmp);
    std::filesystem::rename(tmp, out);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
