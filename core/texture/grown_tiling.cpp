#include "core/texture/grown_tiling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace pmsim {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Without a matrix the upper bounds take each crystal grown to this multiple of its free size: a
// cell no crystal covers even so keeps an infinite bound (correct, but every crystal is then
// listed in it), which a rock's gaps between crystals never come near.
constexpr double kUncappedCover = 4.0;
// Crystals per parallel task: a few thousand gauge windows, well above TBB's scheduling cost.
constexpr int kCrystalBlock = 4096;
}

double growth_fraction(const GrainGrowth& g, const glm::dvec2& p) {
  return gauge(g.shape, glm::dvec3(p.x - g.nucleus_mm.x, p.y - g.nucleus_mm.y, -g.nucleus_mm.z));
}

double arrival_time(const GrainGrowth& g, double s) {
  // Growth times lie in [0, 1] (rock_growth.cpp) and section files keep to > from; a lead of 10³
  // is beyond any time a crystal that does not overgrow reaches a point at.
  constexpr double kOvergrowthLead = 1e3;
  return g.from + s * (g.to - g.from) - (g.overgrows && s <= 1.0 ? kOvergrowthLead : 0.0);
}

double GrownTiling::arrival(int i, const glm::dvec2& p) const {
  const GrainGrowth& g = crystals_[i];
  const double s = growth_fraction(g, p);
  return capped_ && s > 1.0 ? kInf : arrival_time(g, s);
}

int GrownTiling::owner_exhaustive(const glm::dvec2& p) const {
  int best = -1;
  double best_t = kInf;
  for (int i = 0; i < static_cast<int>(crystals_.size()); ++i)
    if (const double t = arrival(i, p); t < best_t) {
      best_t = t;
      best = i;
    }
  return best;
}

int GrownTiling::owner(const glm::dvec2& p) const {
  if (cell_start_.empty()) return owner_exhaustive(p);
  const int cx = std::clamp(static_cast<int>(std::floor((p.x + 0.5 * width_mm_) / cell_mm_)), 0, cells_x_ - 1);
  const int cy = std::clamp(static_cast<int>(std::floor((p.y + 0.5 * height_mm_) / cell_mm_)), 0, cells_y_ - 1);
  const int c = cy * cells_x_ + cx;
  int best = -1;
  double best_t = kInf;
  // Candidates in increasing index: the exhaustive search's winner, ties included.
  for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
    const int i = cell_crystals_[k];
    if (const double t = arrival(i, p); t < best_t) {
      best_t = t;
      best = i;
    }
  }
  return best;
}

// A crystal's growth fractions at the grid nodes of the cells its section can reach (s ≤ 1 in
// 3-D lies within its circumradius R of the nucleus; with growth beyond `to`, within R·s_reach).
struct GrownTiling::NodeWindow {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // cells x0…x1, y0…y1; nodes x0…x1 + 1, y0…y1 + 1
  std::vector<double> s;                 // per node (its capacity kept from crystal to crystal)
  double at(int x, int y) const { return s[static_cast<std::size_t>(y - y0) * (x1 - x0 + 2) + (x - x0)]; }
};

void GrownTiling::window(int i, double s_reach, const glm::dvec2& origin, NodeWindow& w) const {
  w.x0 = w.y0 = 0;
  w.x1 = w.y1 = -1;
  const GrainGrowth& g = crystals_[i];
  const double r3 = g.shape.circumradius_mm * s_reach, z = g.nucleus_mm.z;
  if (!(r3 >= std::abs(z))) return;
  const double reach = std::min(std::sqrt(r3 * r3 - z * z), std::max(width_mm_, height_mm_));
  auto cell = [&](double v, double o, int n) { return std::clamp(static_cast<int>(std::floor((v - o) / cell_mm_)), 0, n - 1); };
  w.x0 = cell(g.nucleus_mm.x - reach, origin.x, cells_x_), w.x1 = cell(g.nucleus_mm.x + reach, origin.x, cells_x_);
  w.y0 = cell(g.nucleus_mm.y - reach, origin.y, cells_y_), w.y1 = cell(g.nucleus_mm.y + reach, origin.y, cells_y_);
  w.s.resize(static_cast<std::size_t>(w.x1 - w.x0 + 2) * (w.y1 - w.y0 + 2));
  std::size_t k = 0;
  for (int y = w.y0; y <= w.y1 + 1; ++y)
    for (int x = w.x0; x <= w.x1 + 1; ++x) w.s[k++] = growth_fraction(g, origin + cell_mm_ * glm::dvec2(x, y));
}

// Upper bounds per cell: arrival is quasi-convex in p (a nondecreasing function of a convex
// gauge), so its maximum over a cell is at a corner; each crystal offers the largest of its four
// corner arrivals to every cell its free-growth section covers (with a matrix; kUncappedCover
// times it without). Crystals in parallel, each thread its own bounds, then their minimum: the
// same bounds in any order.
std::vector<double> GrownTiling::cell_upper_bounds(const glm::dvec2& origin) const {
  const std::size_t cells = static_cast<std::size_t>(cells_x_) * cells_y_;
  tbb::enumerable_thread_specific<std::vector<double>> local([cells] { return std::vector<double>(cells, kInf); });
  const double s_cover = capped_ ? 1.0 : kUncappedCover;
  tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(crystals_.size()), kCrystalBlock), [&](const tbb::blocked_range<int>& range) {
    std::vector<double>& upper = local.local();
    NodeWindow w;
    for (int i = range.begin(); i < range.end(); ++i) {
      const GrainGrowth& g = crystals_[i];
      window(i, s_cover, origin, w);
      for (int y = w.y0; y <= w.y1; ++y)
        for (int x = w.x0; x <= w.x1; ++x) {
          const double s = std::max({w.at(x, y), w.at(x + 1, y), w.at(x, y + 1), w.at(x + 1, y + 1)});
          if (s > s_cover) continue;  // the section of its shape grown that far does not cover this cell
          const double t = arrival_time(g, s);
          double& u = upper[static_cast<std::size_t>(y) * cells_x_ + x];
          u = std::min(u, t + 1e-9 * (std::abs(t) + 1.0));  // rounding margin
        }
    }
  });
  std::vector<double> upper(cells, kInf);
  for (const std::vector<double>& u : local)
    for (std::size_t c = 0; c < cells; ++c) upper[c] = std::min(upper[c], u[c]);
  return upper;
}

// From below, a crystal's growth fraction over a cell is at least its largest corner value less
// diag/h_min (a gauge is Lipschitz with constant 1/h_min, h_min its nearest face), and at least
// d/R (d: 3-D distance from its nucleus to the cell; the gauge is ≥ |x|/R). With a matrix a
// crystal whose bound exceeds 1 never reaches the cell. A crystal is listed in a cell when its
// arrival bound does not exceed the cell's upper bound: the owner is always listed.
void GrownTiling::candidate_cells(int i, const glm::dvec2& origin, const std::vector<double>& upper, double u_max,
                                  NodeWindow& w, std::vector<std::pair<int, int>>& out) const {
  const GrainGrowth& g = crystals_[i];
  const double span = g.to - g.from, R = g.shape.circumradius_mm, diag = cell_mm_ * std::sqrt(2.0);
  // Without a matrix growth goes on past `to`, up to where it passes every cell's upper bound
  // (an overgrowing crystal's whole free-growth shape at least: its lead ends at s = 1).
  const double s_beyond = u_max == kInf ? 1e6 : std::max(0.0, (u_max - g.from) / span);
  const double s_reach = capped_ ? 1.0 : (g.overgrows ? std::max(1.0, s_beyond) : s_beyond);
  window(i, s_reach, origin, w);
  const double h_min = *std::min_element(g.shape.support_mm.begin(), g.shape.support_mm.end());
  for (int y = w.y0; y <= w.y1; ++y)
    for (int x = w.x0; x <= w.x1; ++x) {
      const glm::dvec2 lo = origin + cell_mm_ * glm::dvec2(x, y), hi = lo + glm::dvec2(cell_mm_);
      const double dx = std::max({lo.x - g.nucleus_mm.x, 0.0, g.nucleus_mm.x - hi.x});
      const double dy = std::max({lo.y - g.nucleus_mm.y, 0.0, g.nucleus_mm.y - hi.y});
      const double corner = std::max({w.at(x, y), w.at(x + 1, y), w.at(x, y + 1), w.at(x + 1, y + 1)});
      const double s_low = std::max(std::sqrt(dx * dx + dy * dy + g.nucleus_mm.z * g.nucleus_mm.z) / R, corner - diag / h_min);
      if (capped_ && s_low > 1.0 + 1e-9) continue;
      const double lower = arrival_time(g, s_low);
      const int c = y * cells_x_ + x;
      if (lower - 1e-9 * (std::abs(lower) + 1.0) <= upper[static_cast<std::size_t>(c)]) out.emplace_back(c, i);
    }
}

// Blocks of crystals find their cells in parallel; a stable counting sort by cell, blocks in
// order, then lists every cell's candidates in increasing crystal index.
GrownTiling::GrownTiling(std::vector<GrainGrowth> crystals, bool capped, double width_mm, double height_mm)
    : crystals_(std::move(crystals)), capped_(capped), width_mm_(width_mm), height_mm_(height_mm) {
  const double area = width_mm * height_mm;
  cell_mm_ = std::sqrt(area / std::max<double>(1.0, 2.0 * static_cast<double>(crystals_.size())));
  cell_mm_ = std::max({cell_mm_, width_mm / 1024.0, height_mm / 1024.0});
  cells_x_ = std::max(1, static_cast<int>(std::ceil(width_mm / cell_mm_)));
  cells_y_ = std::max(1, static_cast<int>(std::ceil(height_mm / cell_mm_)));
  const glm::dvec2 origin{-0.5 * width_mm, -0.5 * height_mm};
  const std::vector<double> upper = cell_upper_bounds(origin);
  double u_max = 0.0;
  for (const double u : upper) u_max = std::max(u_max, u);
  const int n = static_cast<int>(crystals_.size()), blocks = (n + kCrystalBlock - 1) / kCrystalBlock;
  std::vector<std::vector<std::pair<int, int>>> found(static_cast<std::size_t>(blocks));  // (cell, crystal)
  tbb::parallel_for(0, blocks, [&](int b) {
    NodeWindow w;
    for (int i = b * kCrystalBlock; i < std::min(n, (b + 1) * kCrystalBlock); ++i) candidate_cells(i, origin, upper, u_max, w, found[b]);
  });
  cell_start_.assign(upper.size() + 1, 0);
  for (const auto& f : found)
    for (const auto& [c, i] : f) ++cell_start_[static_cast<std::size_t>(c) + 1];
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_crystals_.resize(static_cast<std::size_t>(cell_start_.back()));
  std::vector<int> next(cell_start_.begin(), cell_start_.end() - 1);
  for (auto& f : found) {
    for (const auto& [c, i] : f) cell_crystals_[static_cast<std::size_t>(next[static_cast<std::size_t>(c)]++)] = i;
    std::vector<std::pair<int, int>>().swap(f);
  }
}

}  // namespace pmsim
