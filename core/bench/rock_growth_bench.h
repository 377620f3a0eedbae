#pragma once
// Rock growth speed (issue 22's bench row: a 20 × 15 mm section generated in ≤ 2 s and ≤ 1 GB on
// the 2-core machine): every recipe of assets/rocks grown at that size from its own seed and read
// as a section (grow_rock, section_from_grown_rock: what loading sample.section does),
// timed, with the process's peak resident set over it (the previous rock's memory returned to the
// system first: malloc_trim).
#include <cstddef>
#include <string>
#include <vector>

namespace pmsim {

struct RockGrowthBenchRow {
  std::string rock;
  double width_mm = 0.0, height_mm = 0.0;
  std::size_t crystals = 0, grains = 0;  // drawn / in the section
  int rounds = 0;                        // calibration rounds over the section (0 for a granoblastic foam)
  int window_rounds = 0;                 // before them, over the calibration window
  double grow_s = 0.0, section_s = 0.0;  // growth; the section's grains written and read
  long peak_rss_kb = -1, rss_before_kb = -1;
};

std::vector<RockGrowthBenchRow> measure_rock_growth(double width_mm, double height_mm);

// The rows as a markdown table.
std::string rock_growth_table(const std::vector<RockGrowthBenchRow>& rows);

}  // namespace pmsim
