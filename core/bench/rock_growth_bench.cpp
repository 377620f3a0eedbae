#include "core/bench/rock_growth_bench.h"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/base/asset_locator.h"
#include "core/bench/process_memory.h"
#include "core/microscope/section_map.h"
#include "core/texture/rock_growth.h"
#include "core/texture/rock_recipe.h"

namespace pmsim {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::vector<RockGrowthBenchRow> measure_rock_growth(double width_mm, double height_mm) {
  std::vector<std::filesystem::path> recipes;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(asset_dir()) / "rocks"))
    if (e.path().extension() == ".json") recipes.push_back(e.path());
  std::sort(recipes.begin(), recipes.end());
  std::vector<RockGrowthBenchRow> rows;
  for (const auto& path : recipes) {
    RockRecipe r = read_rock_recipe(path.string());
    r.width_mm = width_mm;
    r.height_mm = height_mm;
    RockGrowthBenchRow row;
    row.rock = r.name;
    row.width_mm = width_mm;
    row.height_mm = height_mm;
    // The previous rock's memory back to the system first (glibc keeps freed pages otherwise), so
    // that each row's peak is its own.
    malloc_trim(0);
    row.rss_before_kb = process_status_kb("VmRSS");
    reset_peak_rss();
    const auto t0 = std::chrono::steady_clock::now();
    const RockGrowth g = grow_rock(r, r.seed);
    row.grow_s = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    const SectionMap m = section_from_grown_rock(r, g, r.seed, std::nullopt, path.string());
    row.section_s = seconds_since(t1);
    row.peak_rss_kb = process_status_kb("VmHWM");
    row.crystals = g.crystals.size();
    row.grains = m.grains.size();
    row.rounds = r.granoblastic ? 0 : g.rounds;
    row.window_rounds = g.window_rounds;
    rows.push_back(row);
  }
  return rows;
}

std::string rock_growth_table(const std::vector<RockGrowthBenchRow>& rows) {
  std::ostringstream o;
  o << "| rock | size mm | crystals drawn | grains | calibration rounds (window + section) | growth s | section s | total s | peak RSS MB |\n"
       "|---|---|---|---|---|---|---|---|---|\n";
  o << std::fixed;
  for (const RockGrowthBenchRow& r : rows)
    o << "| " << r.rock << " | " << std::setprecision(0) << r.width_mm << " × " << r.height_mm << " | " << r.crystals
      << " | " << r.grains << " | " << r.window_rounds << " + " << r.rounds << " | " << std::setprecision(2) << r.grow_s << " | " << r.section_s
      << " | " << r.grow_s + r.section_s << " | " << std::setprecision(0)
      << (r.peak_rss_kb >= 0 ? double(r.peak_rss_kb) / 1024.0 : -1.0) << " |\n";
  return o.str();
}

}  // namespace pmsim
