#pragma once
// Process start as a user scripting pmsim-render pays it: an 8×8 PNG render of the default scene
// launched as a new process, timed from spawn to exit (issue 14's target: ≤ 50 ms wall). What
// remains after the lazy OpenImageIO module is the loader, static initialisation, the asset
// libraries and the render itself.
#include <string>

namespace pmsim {

struct ProcessStartResult {
  int runs = 0;
  double median_ms = 0.0, min_ms = 0.0, max_ms = 0.0;  // wall, spawn → exit
  long max_rss_kb = 0;                                 // peak resident set of the slowest-memory run
};

// Runs `render_binary --set render.width=8 --set render.height=8 --out <tmp>.png` `runs` times
// (after one untimed run that warms the page cache). Throws std::runtime_error when a run fails.
ProcessStartResult measure_process_start(const std::string& render_binary, int runs);

}  // namespace pmsim
