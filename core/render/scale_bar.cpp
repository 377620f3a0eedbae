#include "core/render/scale_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/render/dot_matrix_font.h"

namespace pmsim {

namespace {

std::string length_label(double mm) {
  char buf[32];
  if (mm >= 1.0)
    std::snprintf(buf, sizeof buf, "%g mm", mm);
  else
    std::snprintf(buf, sizeof buf, "%g um", std::round(mm * 1000.0 * 1000.0) / 1000.0);
  return buf;
}

}  // namespace

ScaleBar choose_scale_bar(double mm_per_px, int image_width, double max_fraction) {
  const double max_mm = mm_per_px * image_width * max_fraction;
  double best = 0.0;
  for (int e = -4; e <= 4; ++e)
    for (double m : {1.0, 2.0, 5.0}) {
      const double len = m * std::pow(10.0, e);
      if (len <= max_mm * (1 + 1e-12)) best = std::max(best, len);
    }
  if (best <= 0.0) best = 1e-4;
  return {best, best / mm_per_px, length_label(best)};
}

void burn_scale_bar(std::vector<float>& rgb, int width, int height, const ScaleBar& bar) {
  const int s = std::max(1, height / 256);  // glyph pixel size
  auto put = [&](int x, int y, float v) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    float* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    p[0] = p[1] = p[2] = v;
  };
  // A filled box with a black outline one glyph pixel wide.
  auto box = [&](int x0, int y0, int x1, int y1) {
    for (int y = y0 - s; y < y1 + s; ++y)
      for (int x = x0 - s; x < x1 + s; ++x) {
        const bool inside = x >= x0 && x < x1 && y >= y0 && y < y1;
        const float* p = (x >= 0 && y >= 0 && x < width && y < height)
                             ? &rgb[(static_cast<std::size_t>(y) * width + x) * 3]
                             : nullptr;
        if (inside)
          put(x, y, 1.0f);
        else if (p && !(p[0] == 1.0f && p[1] == 1.0f && p[2] == 1.0f))
          put(x, y, 0.0f);
      }
  };
  const int margin = 8 * s;
  const int bar_len = std::max(1, static_cast<int>(std::lround(bar.length_px)));
  const int text_h = 7 * s;
  const int bar_h = 2 * s;
  const int y_text = height - margin - text_h;
  const int y_bar = y_text - 3 * s - bar_h;
  box(margin, y_bar, margin + bar_len, y_bar + bar_h);
  int x = margin;
  for (char c : bar.label) {
    if (const DotMatrixGlyph* g = dot_matrix_glyph(c))
      for (int r = 0; r < 7; ++r)
        for (int col = 0; col < 5; ++col)
          if (g->rows[r] & (0x10 >> col)) box(x + col * s, y_text + r * s, x + (col + 1) * s, y_text + (r + 1) * s);
    x += 6 * s;
  }
}

}  // namespace pmsim
