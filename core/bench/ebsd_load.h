#pragma once
// EBSD map loading speed (issue 13's target: a 1 × 10⁶-point map loads in ≤ 3 s on the 2-core
// machine, with flat memory): a made-up map written as .ctf and as .ang (hexagonal grid) into a
// temporary folder, each read back once with read_orientation_map, timed, with the process's
// peak resident set during the read.
#include <cstddef>
#include <string>
#include <vector>

namespace pmsim {

struct EbsdLoadResult {
  std::string format;  // "ctf (square grid)", "ang (hexagonal grid)"
  std::size_t points = 0;
  double file_mb = 0.0;  // size of the text file
  double load_s = 0.0;   // wall time of read_orientation_map
  double points_per_s = 0.0;
  double map_mb = 0.0;      // the OrientationMap's per-point arrays
  long peak_rss_kb = -1;    // process peak RSS during the read (-1: /proc not available)
  long rss_before_kb = -1;  // process RSS before it
};

// `points` ≈ the map size (rounded to a grid); the files go into a fresh folder under the system
// temporary folder, removed afterwards. Throws std::runtime_error when the files cannot be written.
std::vector<EbsdLoadResult> measure_ebsd_load(std::size_t points);

}  // namespace pmsim
