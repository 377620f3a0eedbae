#include "core/bench/ebsd_load.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/bench/process_memory.h"
#include "core/bench/scratch_dir.h"
#include "core/ebsd/map_writer.h"
#include "core/ebsd/read_orientation_map.h"

namespace pmsim {

namespace {

// A made-up granulite: grains of ~30 points across on a grid, three phases, one point in 23
// non-indexed, angles varying within each grain as a real map's do.
OrientationMap made_up_map(std::size_t points, MapGrid grid) {
  OrientationMap m;
  m.grid = grid;
  const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(points))));
  // Hexagonal rows alternate side + 1 and side points (OIM's NCOLS_ODD = NCOLS_EVEN + 1), so the
  // map holds at least `points`.
  m.columns_odd = grid == MapGrid::Hexagonal ? side + 1 : side;
  m.columns_even = side;
  m.rows = side;
  m.step_x_um = 2.0;
  m.step_y_um = grid == MapGrid::Hexagonal ? std::sqrt(3.0) : 2.0;
  m.vendor = grid == MapGrid::Hexagonal ? EbsdVendor::EdaxTsl : EbsdVendor::OxfordChannel5;
  m.phases = {EbsdPhase{1, "Quartz", "SiO2", UnitCell{4.913, 4.913, 5.405, 90, 90, 120},
                        CrystalSystem::Trigonal, "-3m", "", 154},
              EbsdPhase{2, "Plagioclase", "", UnitCell{8.16, 12.87, 7.11, 93.5, 116.2, 89.6},
                        CrystalSystem::Triclinic, "-1", "", 2},
              EbsdPhase{3, "Garnet", "", UnitCell{11.53, 11.53, 11.53, 90, 90, 90}, CrystalSystem::Cubic,
                        "m-3m", "", 230}};
  m.allocate_points();
  for (std::size_t i = 0; i < m.size(); ++i) {
    const int r = m.row_of(i), c = static_cast<int>(i - m.row_start(r));
    const unsigned grain = static_cast<unsigned>((r / 30) * 7919 + (c / 30) * 104729);
    m.phase[i] = i % 23 == 0 ? 0 : static_cast<std::uint8_t>(1 + grain % 3);
    m.phi1_rad[i] = static_cast<float>(std::fmod(grain * 0.6180339, 6.2831853) + 1e-4 * c);
    m.Phi_rad[i] = static_cast<float>(std::fmod(grain * 0.4142135, 3.1415926));
    m.phi2_rad[i] = static_cast<float>(std::fmod(grain * 0.7320508, 6.2831853) + 1e-4 * r);
  }
  return m;
}

EbsdLoadResult time_load(const std::string& path, const char* format) {
  EbsdLoadResult res;
  res.format = format;
  res.file_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  res.rss_before_kb = process_status_kb("VmRSS");
  reset_peak_rss();
  const auto t0 = std::chrono::steady_clock::now();
  const OrientationMap m = read_orientation_map(path);
  res.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.peak_rss_kb = process_status_kb("VmHWM");
  res.points = m.size();
  res.points_per_s = res.load_s > 0 ? static_cast<double>(m.size()) / res.load_s : 0.0;
  res.map_mb = static_cast<double>(m.phase.size() + 4 * (m.phi1_rad.size() + m.Phi_rad.size() +
                                                         m.phi2_rad.size() + m.quality.size())) /
               1e6;
  return res;
}

}  // namespace

std::vector<EbsdLoadResult> measure_ebsd_load(std::size_t points) {
  const ScratchDir scratch("ebsd");
  const std::filesystem::path& dir = scratch.path();
  std::vector<EbsdLoadResult> out;
  {
    const OrientationMap m = made_up_map(points, MapGrid::Square);
    write_ctf(m, (dir / "map.ctf").string());
  }  // the written map is freed before the timed read
  out.push_back(time_load((dir / "map.ctf").string(), "ctf (square grid)"));
  {
    const OrientationMap m = made_up_map(points, MapGrid::Hexagonal);
    write_ang(m, (dir / "map.ang").string());
  }
  out.push_back(time_load((dir / "map.ang").string(), "ang (hexagonal grid)"));
  return out;
}

}  // namespace pmsim
