#include "core/scene3d/rgb_reflectance_spectrum.h"

#include <algorithm>
#include <array>

namespace pmsim {
namespace {

using Basis = std::array<double, 10>;
// Smits (1999), Table 1 (bins of 34 nm from 380 to 720 nm).
constexpr Basis kWhite{1.0000, 1.0000, 0.9999, 0.9993, 0.9992, 0.9998, 1.0000, 1.0000, 1.0000, 1.0000};
constexpr Basis kCyan{0.9710, 0.9426, 1.0007, 1.0007, 1.0007, 1.0007, 0.1564, 0.0000, 0.0000, 0.0000};
constexpr Basis kMagenta{1.0000, 1.0000, 0.9685, 0.2229, 0.0000, 0.0458, 0.8369, 1.0000, 1.0000, 0.9959};
constexpr Basis kYellow{0.0001, 0.0000, 0.1088, 0.6651, 1.0000, 1.0000, 0.9996, 0.9586, 0.9685, 0.9840};
constexpr Basis kRed{0.1012, 0.0515, 0.0000, 0.0000, 0.0000, 0.0000, 0.8325, 1.0149, 1.0149, 1.0149};
constexpr Basis kGreen{0.0000, 0.0000, 0.0273, 0.7937, 1.0000, 0.9418, 0.1719, 0.0000, 0.0000, 0.0025};
constexpr Basis kBlue{1.0000, 1.0000, 0.8916, 0.3323, 0.0000, 0.0000, 0.0003, 0.0369, 0.0483, 0.0496};

}  // namespace

double smits_reflectance(const glm::dvec3& rgb_linear, double wavelength_nm) {
  const int bin = std::clamp(static_cast<int>((wavelength_nm - 380.0) / 34.0), 0, 9);
  const double r = std::clamp(rgb_linear.x, 0.0, 1.0);
  const double g = std::clamp(rgb_linear.y, 0.0, 1.0);
  const double b = std::clamp(rgb_linear.z, 0.0, 1.0);
  // Smits §3: white·min + complementary·(mid − min) + primary·(max − mid).
  double v;
  if (r <= g && r <= b) {
    v = r * kWhite[bin];
    v += g <= b ? (g - r) * kCyan[bin] + (b - g) * kBlue[bin] : (b - r) * kCyan[bin] + (g - b) * kGreen[bin];
  } else if (g <= r && g <= b) {
    v = g * kWhite[bin];
    v += r <= b ? (r - g) * kMagenta[bin] + (b - r) * kBlue[bin]
                : (b - g) * kMagenta[bin] + (r - b) * kRed[bin];
  } else {
    v = b * kWhite[bin];
    v += r <= g ? (r - b) * kYellow[bin] + (g - r) * kGreen[bin]
                : (g - b) * kYellow[bin] + (r - g) * kRed[bin];
  }
  return std::max(0.0, v);
}

}  // namespace pmsim
