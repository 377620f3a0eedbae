#include "core/render/michel_levy_chart.h"

#include <array>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "core/base/units.h"
#include "core/render/band_integral.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

namespace pmsim {

namespace {
struct Bands {
  static constexpr int n = 400;  // 1 nm
  std::array<glm::dvec3, n> W, M;
};
const Bands& bands(Illuminant il) {
  static std::array<Bands, 2> b;
  static std::once_flag once[2];
  const int k = il == Illuminant::D65 ? 0 : 1;
  std::call_once(once[k], [&] {
    for (int i = 0; i < Bands::n; ++i) {
      glm::dvec3 w(0.0), m(0.0);
      for (int s = 0; s < 4; ++s) {
        const double t = (s + 0.5) * 0.25;
        const glm::dvec3 ws = observer_weight(il, kVisibleMinNm + i + t) * 0.25;
        w += ws;
        m += ws * (t - 0.5);
      }
      b[k].W[i] = w;
      b[k].M[i] = m;
    }
  });
  return b[k];
}
}  // namespace

glm::dvec3 michel_levy_xyz(double gamma_nm, Illuminant il, bool parallel) {
  const Bands& B = bands(il);
  glm::dvec3 xyz(0.0);
  const double two_pi = 2.0 * kPi;
  for (int i = 0; i < Bands::n; ++i) {
    const double lam = kVisibleMinNm + i + 0.5;
    // sin²(πΓ/λ) = (1 − cos(2πΓ/λ))/2; parallel polars: cos²(πΓ/λ) = (1 + cos)/2.
    const glm::dvec3 osc = oscillating_band(B.W[i], B.M[i] * 6.0, two_pi * gamma_nm / lam,
                                            -two_pi * gamma_nm / (lam * lam), 1.0);
    xyz += 0.5 * B.W[i] + (parallel ? 0.5 : -0.5) * osc;
  }
  return xyz;
}

std::vector<float> michel_levy_chart(int width, int height, double max_nm, Illuminant il) {
  std::vector<float> img;
  if (width <= 0 || height <= 0) return img;
  img.resize(static_cast<std::size_t>(width) * height * 3);
  for (int x = 0; x < width; ++x) {
    const glm::dvec3 rgb = xyz_to_linear_srgb(michel_levy_xyz(max_nm * (x + 0.5) / width, il));
    for (int y = 0; y < height; ++y)
      for (int c = 0; c < 3; ++c)
        img[(static_cast<std::size_t>(y) * width + x) * 3 + c] =
            std::isfinite(rgb[c]) ? static_cast<float>(rgb[c]) : 0.0f;
  }
  return img;
}

const std::vector<double>& michel_levy_standard_birefringences() {
  static const std::vector<double> v = {0.001, 0.002, 0.004, 0.006, 0.008, 0.010, 0.012, 0.014, 0.016, 0.018,
                                        0.020, 0.022, 0.024, 0.026, 0.028, 0.030, 0.035, 0.040, 0.045, 0.050,
                                        0.060, 0.070, 0.080, 0.090, 0.100, 0.120, 0.140, 0.160, 0.180, 0.200};
  return v;
}

std::vector<MichelLevyLine> michel_levy_lines(double max_nm, double max_um, const std::vector<double>& dn) {
  std::vector<MichelLevyLine> lines;
  if (!(max_nm > 0) || !(max_um > 0)) return lines;
  for (double b : dn) {
    if (!(b > 0) || !std::isfinite(b)) continue;
    MichelLevyLine l;
    l.birefringence = b;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", b);
    l.label = buf;
    // Γ[nm] = 1000·d[µm]·Δn: at the top edge Γ = 1000·max_um·Δn, else it reaches the right edge
    // at d = max_nm / (1000·Δn).
    const double gamma_top = 1000.0 * max_um * b;
    l.ends_on_top = gamma_top <= max_nm;
    l.to = l.ends_on_top ? glm::dvec2(gamma_top, max_um) : glm::dvec2(max_nm, max_nm / (1000.0 * b));
    l.from_frac = {0.0, 1.0};
    l.to_frac = {l.to.x / max_nm, 1.0 - l.to.y / max_um};
    lines.push_back(l);
  }
  return lines;
}

std::vector<float> michel_levy_chart_with_lines(int width, int height, double max_nm, double max_um,
                                                Illuminant il, const std::vector<double>& dn) {
  std::vector<float> img = michel_levy_chart(width, height, max_nm, il);
  if (img.empty()) return img;
  const std::vector<MichelLevyLine> lines = michel_levy_lines(max_nm, max_um, dn);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // Distance in pixels from the pixel centre to each line (segment from the bottom-left corner).
      const double px = x + 0.5, py = y + 0.5;
      double cover = 0.0;
      for (const MichelLevyLine& l : lines) {
        const double x1 = l.to_frac.x * width, y1 = l.to_frac.y * height, x0 = 0.0, y0 = height;
        const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
        const double t = std::clamp(((px - x0) * dx + (py - y0) * dy) / len2, 0.0, 1.0);
        const double d = std::hypot(px - (x0 + t * dx), py - (y0 + t * dy));
        cover = std::max(cover, std::clamp(1.0 - (d - 0.5), 0.0, 1.0));  // 1 px wide, 1 px falloff
      }
      if (cover <= 0) continue;
      float* c = &img[(static_cast<std::size_t>(y) * width + x) * 3];
      for (int k = 0; k < 3; ++k) c[k] = static_cast<float>(c[k] * (1.0 - 0.85 * cover));
    }
  return img;
}

}  // namespace pmsim
