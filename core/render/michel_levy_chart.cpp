#include "core/render/michel_levy_chart.h"

#include <array>
#include <cmath>
#include <mutex>
#include <numbers>

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
  const double two_pi = 2.0 * std::numbers::pi;
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

}  // namespace pmsim
