#pragma once
// Items listed in the cells of a uniform grid that their bounding boxes meet, each cell's list in
// the order the items were added: a point's candidates are its cell's list. The overgrowth
// cement's forms and the myrmekite bulbs are looked up this way.
#include <span>
#include <vector>

#include <glm/vec2.hpp>

namespace pmsim {

class CellLists {
 public:
  CellLists() = default;
  // A grid from lo_mm to hi_mm in cells cell_mm on a side (at most max_cells a side: larger
  // cells then).
  CellLists(const glm::dvec2& lo_mm, const glm::dvec2& hi_mm, double cell_mm, int max_cells = 2048);
  // Lists `item` in every cell its box [lo, hi] meets (a box beyond the grid: the edge cells).
  void add(int item, const glm::dvec2& lo_mm, const glm::dvec2& hi_mm);
  // The items listed in p's cell; empty outside the grid or before any add.
  std::span<const int> at(const glm::dvec2& p_mm) const;

 private:
  int clamped(double v, double v0, int n) const;
  glm::dvec2 lo_{0.0};
  double cell_mm_ = 1.0;
  int cells_x_ = 0, cells_y_ = 0;
  std::vector<std::vector<int>> lists_;
};

}  // namespace pmsim
