#include "core/texture/grain_packing.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace pmsim {

namespace {

// Balls binned on a periodic horizontal grid over the box, cells at least one largest diameter
// wide: a ball's neighbours are in its cell and the eight around it (modulo the box).
struct PeriodicGrid {
  glm::dvec2 lo{0.0}, size{1.0};
  int nx = 1, ny = 1;
  std::vector<int> start, items;

  PeriodicGrid(const std::vector<glm::dvec3>& c, const glm::dvec2& box_lo, const glm::dvec2& box_hi, double cell_mm)
      : lo(box_lo), size(box_hi - box_lo) {
    nx = std::max(1, static_cast<int>(size.x / cell_mm));
    ny = std::max(1, static_cast<int>(size.y / cell_mm));
    start.assign(std::size_t(nx) * ny + 1, 0);
    std::vector<int> cell_of(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) ++start[std::size_t(cell_of[i] = iy(c[i].y) * nx + ix(c[i].x)) + 1];
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    items.resize(c.size());
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < c.size(); ++i) items[std::size_t(fill[std::size_t(cell_of[i])]++)] = static_cast<int>(i);
  }
  int ix(double x) const { return std::clamp(static_cast<int>((x - lo.x) / size.x * nx), 0, nx - 1); }
  int iy(double y) const { return std::clamp(static_cast<int>((y - lo.y) / size.y * ny), 0, ny - 1); }
  // The cells within one of (cx, cy), each once (a box only one or two cells wide has fewer).
  std::vector<int> around(int cx, int cy) const {
    std::vector<int> cells;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        cells.push_back(((cy + dy + ny) % ny) * nx + (cx + dx + nx) % nx);
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    return cells;
  }
  // The shortest horizontal displacement a − b over the periodic box (minimum image).
  glm::dvec2 displacement(const glm::dvec3& a, const glm::dvec3& b) const {
    glm::dvec2 d{a.x - b.x, a.y - b.y};
    return d - size * glm::round(d / size);
  }
};

}  // namespace

PackingResult pack_balls(std::vector<glm::dvec3>& c, const std::vector<double>& r, const glm::dvec2& box_lo,
                         const glm::dvec2& box_hi, double max_overlap, int max_steps) {
  PackingResult out;
  if (c.size() < 2) return out;
  const double diameter = 2.0 * *std::max_element(r.begin(), r.end());
  std::vector<glm::dvec2> move(c.size());
  for (out.steps = 0; out.steps < max_steps; ++out.steps) {
    const PeriodicGrid grid(c, box_lo, box_hi, diameter);
    std::fill(move.begin(), move.end(), glm::dvec2(0.0));
    out.worst_overlap = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i)
      for (const int cell : grid.around(grid.ix(c[i].x), grid.iy(c[i].y)))
        for (int k = grid.start[std::size_t(cell)]; k < grid.start[std::size_t(cell) + 1]; ++k) {
          const auto j = static_cast<std::size_t>(grid.items[std::size_t(k)]);
          if (j <= i) continue;
          const glm::dvec2 h = grid.displacement(c[i], c[j]);
          const double dz = c[i].z - c[j].z, sum = r[i] + r[j];
          const double h_now = glm::length(h), overlap = (sum - std::sqrt(h_now * h_now + dz * dz)) / sum;
          out.worst_overlap = std::max(out.worst_overlap, overlap);
          if (overlap <= max_overlap) continue;
          // The horizontal separation that brings the 3-D distance to the allowed one; coincident
          // centres part along a direction from their indices (deterministic).
          const double target = sum * (1.0 - max_overlap);
          const double h_need = std::sqrt(std::max(0.0, target * target - dz * dz));
          const double a = double(i * 7919 + j);
          const glm::dvec2 u = h_now > 1e-12 ? h / h_now : glm::dvec2(std::cos(a), std::sin(a));
          move[i] += 0.5 * (h_need - h_now) * u;
          move[j] -= 0.5 * (h_need - h_now) * u;
        }
    if (out.worst_overlap <= max_overlap) break;
    const glm::dvec2 size = box_hi - box_lo;
    for (std::size_t i = 0; i < c.size(); ++i) {  // wrapped back into the box
      glm::dvec2 p = glm::dvec2(c[i]) + move[i] - box_lo;
      p -= size * glm::floor(p / size);
      c[i].x = box_lo.x + p.x, c[i].y = box_lo.y + p.y;
    }
  }
  return out;
}

}  // namespace pmsim
