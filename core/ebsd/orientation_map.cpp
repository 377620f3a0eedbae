#include "core/ebsd/orientation_map.h"

#include <algorithm>

namespace pmsim {

const char* ebsd_vendor_name(EbsdVendor v) {
  return v == EbsdVendor::OxfordChannel5 ? "Oxford Instruments HKL Channel 5" : "EDAX/TSL OIM";
}

std::size_t OrientationMap::row_start(int row) const {
  const std::size_t pair = static_cast<std::size_t>(columns_odd) + static_cast<std::size_t>(columns_even);
  return static_cast<std::size_t>(row / 2) * pair + (row % 2 == 1 ? columns_odd : 0);
}

int OrientationMap::row_of(std::size_t i) const {
  const std::size_t pair = static_cast<std::size_t>(columns_odd) + static_cast<std::size_t>(columns_even);
  const std::size_t r2 = i / pair, rest = i % pair;
  return static_cast<int>(2 * r2 + (rest >= static_cast<std::size_t>(columns_odd) ? 1 : 0));
}

double OrientationMap::x_um(std::size_t i) const {
  const int r = row_of(i);
  const double col = static_cast<double>(i - row_start(r));
  const double shift = (grid == MapGrid::Hexagonal && r % 2 == 1) ? 0.5 * step_x_um : 0.0;
  return col * step_x_um + shift;
}

double OrientationMap::y_um(std::size_t i) const { return row_of(i) * step_y_um; }

double OrientationMap::width_um() const {
  double w = columns_odd > 0 ? (columns_odd - 1) * step_x_um : 0.0;
  if (rows > 1 && columns_even > 0) {
    const double shift = grid == MapGrid::Hexagonal ? 0.5 * step_x_um : 0.0;
    w = std::max(w, (columns_even - 1) * step_x_um + shift);
  }
  return w;
}

void OrientationMap::allocate_points() {
  const std::size_t n = row_start(rows);
  phase.assign(n, 0);
  phi1_rad.assign(n, 0.0f);
  Phi_rad.assign(n, 0.0f);
  phi2_rad.assign(n, 0.0f);
  if (quality_kind != MapQuality::None) quality.assign(n, 0.0f);
}

}  // namespace pmsim
