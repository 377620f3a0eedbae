#include "core/texture/myrmekite.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/base/splitmix64.h"
#include "core/base/units.h"

namespace pmsim {

namespace {
constexpr double kTwoPi = 2.0 * kPi;
// A rod wriggles sideways by this fraction of the rods' spacing, with a wavelength of this many
// spacings along the bulb's depth (the recipe's: rods that meander without merging, as the
// atlases draw them).
constexpr double kWriggle = 0.3, kWriggleWavelength = 2.5;

glm::dvec2 across(const glm::dvec2& out) { return {-out.y, out.x}; }
}  // namespace

bool in_bulb(const MyrmekiteBulb& b, const glm::dvec2& p) {
  const glm::dvec2 d = p - b.root_mm;
  const double u = glm::dot(d, b.out) / b.depth_mm, v = glm::dot(d, across(b.out)) / b.half_width_mm;
  return u >= 0.0 && u * u + v * v <= 1.0;
}

bool in_vermicule(const MyrmekiteBulb& b, const Vermicules& v, const glm::dvec2& p) {
  const glm::dvec2 d = p - b.root_mm;
  const double u = glm::dot(d, b.out), w = glm::dot(d, across(b.out));
  // The fan's apex half a width behind the root: rods from the root spread over about 90°.
  const double rho = b.half_width_mm;
  const double arc = std::atan2(w, u + rho) * (rho + 0.5 * b.depth_mm);
  const double phase = kTwoPi * unit_interval(b.hash), offset = unit_interval(splitmix64(b.hash));
  const double wriggle = kWriggle * v.spacing_mm * std::sin(kTwoPi * u / (kWriggleWavelength * v.spacing_mm) + phase);
  const double q = (arc + wriggle) / v.spacing_mm + offset;
  return q - std::floor(q) < v.width_mm / v.spacing_mm;
}

std::optional<double> ray_exit_mm(const std::function<bool(const glm::dvec2&)>& inside, const glm::dvec2& from,
                                  const glm::dvec2& dir, double reach_mm, double step_mm, double tol_mm) {
  bool entered = false;
  for (double t = 0.0; t <= reach_mm; t += step_mm) {
    if (inside(from + t * dir)) {
      entered = true;
      continue;
    }
    if (!entered) continue;
    double lo = t - step_mm, hi = t;  // inside at lo, outside at hi
    while (hi - lo > tol_mm) {
      const double mid = 0.5 * (lo + hi);
      (inside(from + mid * dir) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
  return std::nullopt;
}

MyrmekiteBulbs::MyrmekiteBulbs(std::vector<MyrmekiteBulb> bulbs, double width_mm, double height_mm)
    : bulbs_(std::move(bulbs)) {
  if (bulbs_.empty()) return;
  double reach = 0.0;
  for (const MyrmekiteBulb& b : bulbs_) reach = std::max({reach, b.depth_mm, b.half_width_mm});
  const glm::dvec2 half{0.5 * width_mm, 0.5 * height_mm};
  cells_ = CellLists(-half, half, 2.0 * reach);
  for (std::size_t k = 0; k < bulbs_.size(); ++k) {
    const double r = std::max(bulbs_[k].depth_mm, bulbs_[k].half_width_mm);
    cells_.add(static_cast<int>(k), bulbs_[k].root_mm - r, bulbs_[k].root_mm + r);
    const auto g = static_cast<std::size_t>(std::max(bulbs_[k].grain, 0));
    if (per_grain_.size() <= g) per_grain_.resize(g + 1, 0);
    per_grain_[g] += bulbs_[k].grain >= 0;
  }
}

int MyrmekiteBulbs::count_of(int grain) const {
  const auto g = static_cast<std::size_t>(grain);
  return grain >= 0 && g < per_grain_.size() ? per_grain_[g] : 0;
}

int MyrmekiteBulbs::at(const glm::dvec2& p) const {
  for (const int k : cells_.at(p))
    if (in_bulb(bulbs_[static_cast<std::size_t>(k)], p)) return k;
  return -1;
}

}  // namespace pmsim
