#include "core/texture/grain_packing.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace pmsim {

namespace {

// Balls binned on a periodic horizontal grid over the box. The cells are one mean diameter wide,
// not one largest: a sand's sizes are spread (rock_recipe.h, log-normal sorting), and cells sized
// for its rare coarsest grain put dozens of fine ones in every neighbourhood. A ball of radius r
// can overlap only balls within r + r_max, so its search reaches that many cells.
struct PeriodicGrid {
  glm::dvec2 lo{0.0}, size{1.0};
  int nx = 1, ny = 1;
  double cell_mm = 1.0;
  std::vector<int> start, items;

  PeriodicGrid(const std::vector<glm::dvec3>& c, const glm::dvec2& box_lo, const glm::dvec2& box_hi, double cell)
      : lo(box_lo), size(box_hi - box_lo) {
    nx = std::max(1, static_cast<int>(size.x / cell));
    ny = std::max(1, static_cast<int>(size.y / cell));
    cell_mm = std::min(size.x / nx, size.y / ny);
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
  // Calls f(item) for every ball in the cells within reach_mm of (cx, cy)'s cell, each cell once
  // (a box fewer cells wide than the reach is visited whole).
  template <class F>
  void for_each_near(int cx, int cy, double reach_mm, F&& f) const {
    const int reach = static_cast<int>(std::ceil(reach_mm / cell_mm));
    const bool all_x = 2 * reach + 1 >= nx, all_y = 2 * reach + 1 >= ny;
    const int x0 = all_x ? 0 : cx - reach, x1 = all_x ? nx - 1 : cx + reach;
    const int y0 = all_y ? 0 : cy - reach, y1 = all_y ? ny - 1 : cy + reach;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const auto cell = std::size_t(((y + ny) % ny) * nx + (x + nx) % nx);
        for (int k = start[cell]; k < start[cell + 1]; ++k) f(static_cast<std::size_t>(items[std::size_t(k)]));
      }
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
  const double r_max = *std::max_element(r.begin(), r.end());
  double r_sum = 0.0;
  for (const double ri : r) r_sum += ri;
  const double mean_diameter = 2.0 * r_sum / double(r.size());
  std::vector<glm::dvec2> move(c.size());
  for (out.steps = 0; out.steps < max_steps; ++out.steps) {
    const PeriodicGrid grid(c, box_lo, box_hi, mean_diameter);
    std::fill(move.begin(), move.end(), glm::dvec2(0.0));
    out.worst_overlap = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i)
      grid.for_each_near(grid.ix(c[i].x), grid.iy(c[i].y), r[i] + r_max, [&](std::size_t j) {
          if (j <= i) return;
          const glm::dvec2 h = grid.displacement(c[i], c[j]);
          const double dz = c[i].z - c[j].z, sum = r[i] + r[j];
          const double h_now = glm::length(h), overlap = (sum - std::sqrt(h_now * h_now + dz * dz)) / sum;
          out.worst_overlap = std::max(out.worst_overlap, overlap);
          if (overlap <= max_overlap) return;
          // The horizontal separation that brings the 3-D distance to the allowed one; coincident
          // centres part along a direction from their indices (deterministic).
          const double target = sum * (1.0 - max_overlap);
          const double h_need = std::sqrt(std::max(0.0, target * target - dz * dz));
          const double a = double(i * 7919 + j);
          const glm::dvec2 u = h_now > 1e-12 ? h / h_now : glm::dvec2(std::cos(a), std::sin(a));
          move[i] += 0.5 * (h_need - h_now) * u;
          move[j] -= 0.5 * (h_need - h_now) * u;
        });
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
