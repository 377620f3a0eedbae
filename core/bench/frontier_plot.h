#pragma once
// The frontier plot: wall time (log scale) against mean CIEDE2000 (log scale), one point per
// (scene, strategy) row, colour by strategy family, marker by scene, drawn into an RGB buffer with
// a built-in 5×7 bitmap font (no plotting library), written as PNG through core/io.
#include <cstdint>
#include <string>
#include <vector>

#include "core/bench/bench_run.h"

namespace pmsim {

struct RgbCanvas {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // top row first
  RgbCanvas(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 255) {}
  void set(int x, int y, const std::uint8_t c[3]);
  void line(int x0, int y0, int x1, int y1, const std::uint8_t c[3], bool dashed = false);
  void rect(int x0, int y0, int x1, int y1, const std::uint8_t c[3], bool fill);
  // 5×7 glyphs scaled by `scale`; lower case is drawn as upper case; unknown characters as blanks.
  void text(int x, int y, const std::string& s, const std::uint8_t c[3], int scale = 1);
  static int text_width(const std::string& s, int scale = 1);
};

RgbCanvas frontier_plot(const BenchReport& report, int width = 1000, int height = 640);
// Atomic PNG write (core/io write_image_rgb8).
void write_frontier_plot(const BenchReport& report, const std::string& path);

}  // namespace pmsim
