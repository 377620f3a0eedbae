#include "core/bench/frontier_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include "core/io/image_file.h"
#include "core/render/dot_matrix_font.h"

namespace pmsim {

namespace {

constexpr std::uint8_t kBlack[3] = {0, 0, 0}, kGrey[3] = {200, 200, 200}, kDark[3] = {90, 90, 90};

struct Family {
  const char* prefix;
  const char* label;
  std::uint8_t colour[3];
};
constexpr Family kFamilies[] = {
    {"uniform", "uniform (exact, n bands)", {31, 119, 180}},
    {"rgb", "RGB 3 wavelengths", {214, 39, 40}},
    {"stratified", "stratified per pixel", {255, 127, 14}},
    {"hero", "hero wavelength", {148, 103, 189}},
    {"modal", "modal fit, n bands", {44, 160, 44}},
    {"auto", "renderer auto (converged)", {0, 0, 0}},
    {"first-pass", "first progressive pass", {140, 86, 75}},
    {"second-pass", "second progressive pass", {196, 156, 148}},
    {"stage-drag", "stage drag, mean frame to converged", {255, 0, 255}},
    {"reference", "reference, half samples", {127, 127, 127}},
    {"ideal", "ideal lenses", {23, 190, 207}},
    {"sml", "bench SML lenses dT / Schlick", {188, 189, 34}},
    {"renderer-", "renderer physical lenses", {227, 119, 194}},
};

const Family& family_of(const std::string& strategy) {
  for (const Family& f : kFamilies)
    if (strategy.rfind(f.prefix, 0) == 0) return f;
  return kFamilies[0];
}

}  // namespace

void RgbCanvas::set(int x, int y, const std::uint8_t c[3]) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  p[0] = c[0], p[1] = c[1], p[2] = c[2];
}

void RgbCanvas::line(int x0, int y0, int x1, int y1, const std::uint8_t c[3], bool dashed) {
  // Bresenham.
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy, k = 0;
  for (;;) {
    if (!dashed || (k / 4) % 2 == 0) set(x0, y0, c);
    ++k;
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) err += dy, x0 += sx;
    if (e2 <= dx) err += dx, y0 += sy;
  }
}

void RgbCanvas::rect(int x0, int y0, int x1, int y1, const std::uint8_t c[3], bool fill) {
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x)
      if (fill || y == y0 || y == y1 || x == x0 || x == x1) set(x, y, c);
}

void RgbCanvas::text(int x, int y, const std::string& s, const std::uint8_t c[3], int scale) {
  for (char ch : s) {
    if (const DotMatrixGlyph* g = dot_matrix_glyph(ch))
      for (int r = 0; r < 7; ++r)
        for (int col = 0; col < 5; ++col)
          if (g->rows[r] & (0x10 >> col))
            rect(x + col * scale, y + r * scale, x + (col + 1) * scale - 1, y + (r + 1) * scale - 1, c, true);
    x += 6 * scale;
  }
}

int RgbCanvas::text_width(const std::string& s, int scale) { return static_cast<int>(s.size()) * 6 * scale; }

RgbCanvas frontier_plot(const BenchReport& rep, int W, int H) {
  RgbCanvas cv(W, H);
  const int left = 70, right = W - 300, top = 40, bottom = H - 60;
  // Ranges (decades).
  double tmin = 1e300, tmax = 0, emin = 1e300, emax = 0;
  for (const BenchRow& r : rep.rows) {
    if (r.time_ms <= 0.0) continue;  // a reference read from the cache: no time to show
    tmin = std::min(tmin, std::max(r.time_ms, 0.01));
    tmax = std::max(tmax, std::max(r.time_ms, 0.01));
    emin = std::min(emin, std::max(r.mean_de2000, 1e-3));
    emax = std::max(emax, std::max(r.mean_de2000, 1e-3));
  }
  if (rep.rows.empty()) tmin = 1, tmax = 10, emin = 0.01, emax = 10;
  const int tx0 = static_cast<int>(std::floor(std::log10(tmin))),
            tx1 = std::max(tx0 + 1, static_cast<int>(std::ceil(std::log10(tmax))));
  const int ey0 = static_cast<int>(std::floor(std::log10(emin))),
            ey1 = std::max(ey0 + 1, static_cast<int>(std::ceil(std::log10(emax))));
  auto X = [&](double t) {
    return left + static_cast<int>((std::log10(std::max(t, 0.01)) - tx0) / (tx1 - tx0) * (right - left));
  };
  auto Y = [&](double e) {
    return bottom - static_cast<int>((std::log10(std::max(e, 1e-3)) - ey0) / (ey1 - ey0) * (bottom - top));
  };
  for (int d = tx0; d <= tx1; ++d) {
    cv.line(X(std::pow(10.0, d)), top, X(std::pow(10.0, d)), bottom, kGrey);
    const std::string s =
        d >= 0 ? std::to_string(static_cast<long>(std::pow(10.0, d))) : "0." + std::string(-d - 1, '0') + "1";
    cv.text(X(std::pow(10.0, d)) - RgbCanvas::text_width(s) / 2, bottom + 8, s, kBlack);
  }
  for (int d = ey0; d <= ey1; ++d) {
    cv.line(left, Y(std::pow(10.0, d)), right, Y(std::pow(10.0, d)), kGrey);
    const std::string s =
        d >= 0 ? std::to_string(static_cast<long>(std::pow(10.0, d))) : "0." + std::string(-d - 1, '0') + "1";
    cv.text(left - 8 - RgbCanvas::text_width(s), Y(std::pow(10.0, d)) - 3, s, kBlack);
  }
  // Targets: ΔE = 1 and 5, 16 ms and 33 ms.
  if (ey0 <= 0 && ey1 >= 0) cv.line(left, Y(1.0), right, Y(1.0), kDark, true);
  if (std::log10(5.0) >= ey0 && std::log10(5.0) <= ey1) cv.line(left, Y(5.0), right, Y(5.0), kDark, true);
  for (double t : {16.0, 33.0})
    if (std::log10(t) >= tx0 && std::log10(t) <= tx1) cv.line(X(t), top, X(t), bottom, kDark, true);
  cv.rect(left, top, right, bottom, kBlack, false);
  cv.text(left, 12,
          "PMSIM-BENCH: TIME VS MEAN CIEDE2000 (" + std::to_string(rep.options.size) + "X" +
              std::to_string(rep.options.size) + ")",
          kBlack, 2);
  cv.text((left + right) / 2 - RgbCanvas::text_width("WALL TIME (MS), LOG") / 2, bottom + 26,
          "WALL TIME (MS), LOG", kBlack);
  cv.text(6, top - 14, "MEAN DE2000, LOG", kBlack);
  // Scenes → marker shapes.
  std::map<std::string, int> scene_index;
  for (const BenchRow& r : rep.rows) scene_index.emplace(r.scene, static_cast<int>(scene_index.size()));
  auto marker = [&](int x, int y, int shape, const std::uint8_t c[3]) {
    switch (shape % 5) {
      case 0:  // filled disk
        for (int dy = -4; dy <= 4; ++dy)
          for (int dx = -4; dx <= 4; ++dx)
            if (dx * dx + dy * dy <= 16) cv.set(x + dx, y + dy, c);
        break;
      case 1:
        cv.rect(x - 4, y - 4, x + 4, y + 4, c, true);
        break;
      case 2:  // triangle
        for (int dy = -4; dy <= 4; ++dy)
          for (int dx = -(dy + 4) / 2; dx <= (dy + 4) / 2; ++dx) cv.set(x + dx, y + dy, c);
        break;
      case 3:  // diamond
        for (int dy = -5; dy <= 5; ++dy)
          for (int dx = -(5 - std::abs(dy)); dx <= 5 - std::abs(dy); ++dx) cv.set(x + dx, y + dy, c);
        break;
      default:  // cross
        for (int d = -5; d <= 5; ++d) {
          cv.set(x + d, y + d, c), cv.set(x + d, y - d, c), cv.set(x + d + 1, y + d, c),
              cv.set(x + d + 1, y - d, c);
        }
    }
  };
  for (const BenchRow& r : rep.rows)
    if (r.time_ms > 0.0)
      marker(X(r.time_ms), Y(r.mean_de2000), scene_index[r.scene], family_of(r.strategy).colour);
  // Legend.
  int ly = top;
  const int lx = right + 16;
  cv.text(lx, ly, "STRATEGY (COLOUR)", kBlack);
  ly += 14;
  for (const Family& f : kFamilies) {
    bool used = false;
    for (const BenchRow& r : rep.rows) used |= &family_of(r.strategy) == &f;
    if (!used) continue;
    cv.rect(lx, ly, lx + 8, ly + 7, f.colour, true);
    cv.text(lx + 14, ly, f.label, kBlack);
    ly += 12;
  }
  ly += 10;
  cv.text(lx, ly, "SCENE (MARKER)", kBlack);
  ly += 14;
  for (const auto& [name, idx] : scene_index) {
    marker(lx + 4, ly + 3, idx, kDark);
    cv.text(lx + 14, ly, name, kBlack);
    ly += 14;
  }
  ly += 10;
  cv.text(lx, ly, "DASHED: DE 1 AND 5,", kDark);
  cv.text(lx, ly + 10, "16 MS AND 33 MS", kDark);
  return cv;
}

void write_frontier_plot(const BenchReport& rep, const std::string& path) {
  const RgbCanvas cv = frontier_plot(rep);
  write_image_rgb8(path, cv.width, cv.height, cv.rgb, nlohmann::json{{"pmsim:bench", "frontier plot"}});
}

}  // namespace pmsim
