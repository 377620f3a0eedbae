#include "core/texture/cell_lists.h"

#include <algorithm>
#include <cmath>

namespace pmsim {

CellLists::CellLists(const glm::dvec2& lo_mm, const glm::dvec2& hi_mm, double cell_mm, int max_cells) : lo_(lo_mm) {
  const glm::dvec2 extent = hi_mm - lo_mm;
  cell_mm_ = std::max({cell_mm, extent.x / max_cells, extent.y / max_cells});
  cells_x_ = std::max(1, static_cast<int>(std::ceil(extent.x / cell_mm_)));
  cells_y_ = std::max(1, static_cast<int>(std::ceil(extent.y / cell_mm_)));
  lists_.resize(static_cast<std::size_t>(cells_x_) * cells_y_);
}

int CellLists::clamped(double v, double v0, int n) const {
  return std::clamp(static_cast<int>(std::floor((v - v0) / cell_mm_)), 0, n - 1);
}

void CellLists::add(int item, const glm::dvec2& lo_mm, const glm::dvec2& hi_mm) {
  for (int cy = clamped(lo_mm.y, lo_.y, cells_y_); cy <= clamped(hi_mm.y, lo_.y, cells_y_); ++cy)
    for (int cx = clamped(lo_mm.x, lo_.x, cells_x_); cx <= clamped(hi_mm.x, lo_.x, cells_x_); ++cx)
      lists_[static_cast<std::size_t>(cy) * cells_x_ + cx].push_back(item);
}

std::span<const int> CellLists::at(const glm::dvec2& p) const {
  if (lists_.empty()) return {};
  const double fx = std::floor((p.x - lo_.x) / cell_mm_), fy = std::floor((p.y - lo_.y) / cell_mm_);
  if (!(fx >= 0.0 && fy >= 0.0 && fx < cells_x_ && fy < cells_y_)) return {};
  return lists_[static_cast<std::size_t>(fy) * cells_x_ + static_cast<std::size_t>(fx)];
}

}  // namespace pmsim
