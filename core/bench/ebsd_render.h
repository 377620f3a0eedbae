#pragma once
// EBSD map rendering speed (issue 13's targets on the 2-core machine, a 1 × 10⁶-point map: load
// ≤ 3 s, first image ≤ 100 ms, converged 1024² image between crossed polars ≤ 1 s): the made-up
// quartzite of core/ebsd/example_map.h, side × side points 5 µm apart, written as .ctf into a
// temporary folder and looked at through the 4× objective (a 5 mm field: the whole map).
//   load:       load_map_section (read, phase mapping, grains and clusters: what a scene pays once);
//   first:      the interactive renderer's first image after a restart, the map already loaded (a
//               new renderer: its image buffers are touched for the first time, as in an app's
//               first view of the map; later restarts reuse them);
//   converged:  pmsim-render's render to convergence (render.tolerance 0.5 ΔE00).
// Speed is paired with error: the first image's mean ΔE00 against the converged one, and the
// converged image's own error estimate.
#include <cstddef>
#include <string>

namespace pmsim {

struct EbsdRenderResult {
  std::size_t points = 0, grains = 0, clusters = 0;
  double load_s = 0.0;
  double first_ms = 0.0, first_cpu_ms = 0.0;  // wall; process CPU (all threads; /cores ≈ unloaded wall)
  double first_vs_converged_mean_de2000 = 0.0;
  double converged_ms = 0.0, converged_cpu_ms = 0.0;
  double converged_error_estimate = -1.0;
  int width = 0, height = 0;
};

// Throws std::runtime_error when the file cannot be written.
EbsdRenderResult measure_ebsd_render(std::size_t points, int threads = 0);

}  // namespace pmsim
