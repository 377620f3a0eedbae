#include "core/texture/grown_tiling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>

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
constexpr std::size_t kCrystalBlock = 4096;
// The grid nodes' growth fractions are computed incrementally (window()): off the exact gauge by a
// few ulps of values ≲ 10², far below this relative allowance, which the bounds take against
// themselves (the upper ones up, the lower ones down).
constexpr double kNodeRounding = 1e-12;
}  // namespace

double growth_fraction(const GrainGrowth& g, const glm::dvec2& p) {
  return gauge(g.shape, glm::dvec3(p.x - g.nucleus_mm.x, p.y - g.nucleus_mm.y, -g.nucleus_mm.z));
}

double arrival_time(const GrainGrowth& g, double s) {
  // Growth times lie in [0, 1] (rock_growth.cpp) and section files keep to > from; a lead of 10³
  // is beyond any time a crystal that does not overgrow reaches a point at.
  constexpr double kOvergrowthLead = 1e3;
  return g.from + s * (g.to - g.from) - (g.overgrows && s <= 1.0 ? kOvergrowthLead : 0.0);
}

namespace {

// Every crystal's shape from shape_of(i, faces) (which appends its faces and returns its record),
// blocks of kCrystalBlock crystals in parallel, each block's faces in one array, then joined.
template <class ShapeOf>
void fill_shapes(std::size_t n, std::vector<GrownTiling::Shape>& shapes, std::vector<glm::dvec4>& faces, ShapeOf shape_of) {
  shapes.resize(n);
  const std::size_t blocks = (n + kCrystalBlock - 1) / kCrystalBlock;
  std::vector<std::vector<glm::dvec4>> block_faces(blocks);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    for (std::size_t i = b * kCrystalBlock; i < std::min(n, (b + 1) * kCrystalBlock); ++i) shapes[i] = shape_of(i, block_faces[b]);
  });
  std::vector<std::size_t> offset(blocks + 1, 0);
  for (std::size_t b = 0; b < blocks; ++b) offset[b + 1] = offset[b] + block_faces[b].size();
  faces.resize(offset.back());
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    std::copy(block_faces[b].begin(), block_faces[b].end(), faces.begin() + static_cast<std::ptrdiff_t>(offset[b]));
    for (std::size_t i = b * kCrystalBlock; i < std::min(n, (b + 1) * kCrystalBlock); ++i)
      shapes[i].first_face += static_cast<std::uint32_t>(offset[b]);
    std::vector<glm::dvec4>().swap(block_faces[b]);
  });
}

// A crystal's record from its normals and supports (normal(f), support(f), f < count), appending
// one face per opposite pair when every face has its exact opposite next to it.
template <class Normal, class Support>
GrownTiling::Shape shape_record(const glm::dvec3& nucleus, double from, double to, bool overgrows, std::size_t count,
                                Normal normal, Support support, double circumradius, std::vector<glm::dvec4>& faces) {
  GrownTiling::Shape s;
  s.nucleus_mm = nucleus;
  s.from = from;
  s.span = to - from;
  s.overgrows = overgrows;
  s.circumradius_mm = circumradius;
  s.first_face = static_cast<std::uint32_t>(faces.size());
  if (count == 0) {
    s.ball_mm = support(0);
    s.h_min = s.ball_mm;
    return s;
  }
  const std::size_t start = faces.size();
  s.h_min = kInf;
  for (std::size_t f = 0; f < count; ++f) {
    const double h = support(f);
    faces.emplace_back(normal(f), h);
    s.h_min = std::min(s.h_min, h);
  }
  s.paired = count % 2 == 0;
  for (std::size_t f = 0; s.paired && f < count; f += 2) {
    const glm::dvec4 &a = faces[start + f], &b = faces[start + f + 1];
    s.paired = b.x == -a.x && b.y == -a.y && b.z == -a.z && b.w == a.w;
  }
  if (s.paired) {
    for (std::size_t f = 0; f < count / 2; ++f) faces[start + f] = faces[start + 2 * f];
    faces.resize(start + count / 2);
  }
  // Nearest faces first: beyond() stops at the first face out of reach, most often a lath's or
  // plate's broad face (the gauge is their maximum, in any order).
  std::stable_sort(faces.begin() + static_cast<std::ptrdiff_t>(start), faces.end(),
                   [](const glm::dvec4& a, const glm::dvec4& b) { return a.w < b.w; });
  s.faces = static_cast<std::uint16_t>(faces.size() - start);
  return s;
}

}  // namespace

GrownTiling::GrownTiling(const std::vector<GrainGrowth>& crystals, bool capped, double width_mm, double height_mm)
    : GrownTiling(
          crystals.size(), [&](std::size_t i) -> const GrainGrowth& { return crystals[i]; }, capped, width_mm, height_mm) {}

GrownTiling::GrownTiling(std::size_t n, const std::function<const GrainGrowth&(std::size_t)>& crystal, bool capped,
                         double width_mm, double height_mm)
    : capped_(capped), width_mm_(width_mm), height_mm_(height_mm) {
  fill_shapes(n, shapes_, faces_, [&](std::size_t i, std::vector<glm::dvec4>& faces) {
    const GrainGrowth& g = crystal(i);
    const CrystalPolyhedron& p = g.shape;
    return shape_record(
        g.nucleus_mm, g.from, g.to, g.overgrows, p.normals.size(), [&](std::size_t f) { return p.normals[f]; },
        [&](std::size_t f) { return p.support_mm[f]; }, p.circumradius_mm, faces);
  });
  build();
}

GrownTiling::GrownTiling(std::size_t n, const std::function<PlacedGrowth(std::size_t)>& crystal, bool capped,
                         double width_mm, double height_mm)
    : capped_(capped), width_mm_(width_mm), height_mm_(height_mm) {
  fill_shapes(n, shapes_, faces_, [&](std::size_t i, std::vector<glm::dvec4>& faces) {
    const PlacedGrowth g = crystal(i);
    const CrystalPolyhedron& u = *g.unit;
    // As placed(): normals turned by L, supports and circumradius times the size.
    return shape_record(
        g.nucleus_mm, g.from, g.to, g.overgrows, u.normals.size(), [&](std::size_t f) { return g.L * u.normals[f]; },
        [&](std::size_t f) { return u.support_mm[f] * g.size_mm; }, u.circumradius_mm * g.size_mm, faces);
  });
  build();
}

// growth_fraction of the crystal's polyhedron, the same number.
double GrownTiling::fraction(int i, const glm::dvec2& p) const {
  const Shape& c = shapes_[static_cast<std::size_t>(i)];
  const glm::dvec3 x(p.x - c.nucleus_mm.x, p.y - c.nucleus_mm.y, -c.nucleus_mm.z);
  if (c.faces == 0) return glm::length(x) / c.ball_mm;
  const glm::dvec4* f = faces_.data() + c.first_face;
  double g = 0.0;
  if (c.paired)
    for (int k = 0; k < c.faces; ++k) g = std::max(g, std::abs(glm::dot(glm::dvec3(f[k]), x) / f[k].w));
  else
    for (int k = 0; k < c.faces; ++k) g = std::max(g, glm::dot(glm::dvec3(f[k]), x) / f[k].w);
  return g;
}

// True only where fraction(i, p) > 1: some face's n·x exceeds its h by more than the rounding
// of n·x/h. A multiplication a face, where the fraction divides: most of a cell's candidates do not
// reach a given point of it.
bool GrownTiling::beyond(int i, const glm::dvec2& p) const {
  const Shape& c = shapes_[static_cast<std::size_t>(i)];
  if (c.faces == 0) return false;
  const glm::dvec3 x(p.x - c.nucleus_mm.x, p.y - c.nucleus_mm.y, -c.nucleus_mm.z);
  const glm::dvec4* f = faces_.data() + c.first_face;
  for (int k = 0; k < c.faces; ++k) {
    const double d = glm::dot(glm::dvec3(f[k]), x), limit = f[k].w * (1.0 + 1e-9);
    if ((c.paired ? std::abs(d) : d) > limit) return true;
  }
  return false;
}

// arrival_time of the crystal, the same number.
double GrownTiling::arrival_at(int i, double s) const {
  constexpr double kOvergrowthLead = 1e3;
  const Shape& c = shapes_[static_cast<std::size_t>(i)];
  return c.from + s * c.span - (c.overgrows && s <= 1.0 ? kOvergrowthLead : 0.0);
}

double GrownTiling::arrival(int i, const glm::dvec2& p) const {
  if (capped_ && beyond(i, p)) return kInf;
  const double s = fraction(i, p);
  return capped_ && s > 1.0 ? kInf : arrival_at(i, s);
}

int GrownTiling::owner_exhaustive(const glm::dvec2& p) const {
  int best = -1;
  double best_t = kInf;
  for (int i = 0; i < static_cast<int>(shapes_.size()); ++i)
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
  const Shape& g = shapes_[static_cast<std::size_t>(i)];
  const double r3 = g.circumradius_mm * s_reach, z = g.nucleus_mm.z;
  if (!(r3 >= std::abs(z))) return;
  const double reach = std::min(std::sqrt(r3 * r3 - z * z), std::max(width_mm_, height_mm_));
  auto cell = [&](double v, double o, int n) { return std::clamp(static_cast<int>(std::floor((v - o) / cell_mm_)), 0, n - 1); };
  w.x0 = cell(g.nucleus_mm.x - reach, origin.x, cells_x_), w.x1 = cell(g.nucleus_mm.x + reach, origin.x, cells_x_);
  w.y0 = cell(g.nucleus_mm.y - reach, origin.y, cells_y_), w.y1 = cell(g.nucleus_mm.y + reach, origin.y, cells_y_);
  const int nx = w.x1 - w.x0 + 2, ny = w.y1 - w.y0 + 2;
  w.s.resize(static_cast<std::size_t>(nx) * ny);
  if (g.faces == 0) {
    std::size_t k = 0;
    for (int y = w.y0; y <= w.y1 + 1; ++y)
      for (int x = w.x0; x <= w.x1 + 1; ++x) w.s[k++] = fraction(i, origin + cell_mm_ * glm::dvec2(x, y));
    return;
  }
  // Each face's n·x/h is linear over the grid: its value at the first node plus steps along x and
  // y (bounds only: the few ulps this differs from fraction() are within kNodeRounding).
  std::fill(w.s.begin(), w.s.end(), 0.0);
  const glm::dvec2 first = origin + cell_mm_ * glm::dvec2(w.x0, w.y0);
  const glm::dvec3 x0(first.x - g.nucleus_mm.x, first.y - g.nucleus_mm.y, -g.nucleus_mm.z);
  const glm::dvec4* f = faces_.data() + g.first_face;
  for (int k = 0; k < g.faces; ++k) {
    const glm::dvec3 n(f[k]);
    const double base = glm::dot(n, x0) / f[k].w, ax = n.x * cell_mm_ / f[k].w, ay = n.y * cell_mm_ / f[k].w;
    for (int y = 0; y < ny; ++y) {
      double* row = w.s.data() + static_cast<std::size_t>(y) * nx;
      const double b = base + y * ay;
      if (g.paired)
        for (int x = 0; x < nx; ++x) row[x] = std::max(row[x], std::abs(b + x * ax));
      else
        for (int x = 0; x < nx; ++x) row[x] = std::max(row[x], b + x * ax);
    }
  }
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
  tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(shapes_.size()), static_cast<int>(kCrystalBlock)), [&](const tbb::blocked_range<int>& range) {
    std::vector<double>& upper = local.local();
    NodeWindow w;
    for (int i = range.begin(); i < range.end(); ++i) {
      window(i, s_cover, origin, w);
      for (int y = w.y0; y <= w.y1; ++y)
        for (int x = w.x0; x <= w.x1; ++x) {
          double s = std::max({w.at(x, y), w.at(x + 1, y), w.at(x, y + 1), w.at(x + 1, y + 1)});
          s += kNodeRounding * (1.0 + s);  // at least the exact corner value
          if (s > s_cover) continue;  // the section of its shape grown that far does not cover this cell
          const double t = arrival_at(i, s);
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
  const Shape& g = shapes_[static_cast<std::size_t>(i)];
  const double span = g.span, R = g.circumradius_mm, diag = cell_mm_ * std::sqrt(2.0);
  // Without a matrix growth goes on past `to`, up to where it passes every cell's upper bound
  // (an overgrowing crystal's whole free-growth shape at least: its lead ends at s = 1).
  const double s_beyond = u_max == kInf ? 1e6 : std::max(0.0, (u_max - g.from) / span);
  const double s_reach = capped_ ? 1.0 : (g.overgrows ? std::max(1.0, s_beyond) : s_beyond);
  window(i, s_reach, origin, w);
  const double lipschitz_drop = diag / g.h_min;
  for (int y = w.y0; y <= w.y1; ++y)
    for (int x = w.x0; x <= w.x1; ++x) {
      double corner = std::max({w.at(x, y), w.at(x + 1, y), w.at(x, y + 1), w.at(x + 1, y + 1)});
      corner -= kNodeRounding * (1.0 + corner);  // at most the exact corner value
      const double s_faces = corner - lipschitz_drop;
      if (capped_ && s_faces > 1.0 + 1e-9) continue;  // before the distance's square root
      const glm::dvec2 lo = origin + cell_mm_ * glm::dvec2(x, y), hi = lo + glm::dvec2(cell_mm_);
      const double dx = std::max({lo.x - g.nucleus_mm.x, 0.0, g.nucleus_mm.x - hi.x});
      const double dy = std::max({lo.y - g.nucleus_mm.y, 0.0, g.nucleus_mm.y - hi.y});
      const double s_low = std::max(std::sqrt(dx * dx + dy * dy + g.nucleus_mm.z * g.nucleus_mm.z) / R, s_faces);
      if (capped_ && s_low > 1.0 + 1e-9) continue;
      const double lower = arrival_at(i, s_low);
      const int c = y * cells_x_ + x;
      if (lower - 1e-9 * (std::abs(lower) + 1.0) <= upper[static_cast<std::size_t>(c)]) out.emplace_back(c, i);
    }
}

// Blocks of crystals find their cells in parallel; a stable counting sort by cell, blocks in
// order, then lists every cell's candidates in increasing crystal index.
void GrownTiling::build() {
  const double area = width_mm_ * height_mm_;
  const double width_mm = width_mm_, height_mm = height_mm_;
  cell_mm_ = std::sqrt(area / std::max<double>(1.0, 2.0 * static_cast<double>(shapes_.size())));
  cell_mm_ = std::max({cell_mm_, width_mm / 1024.0, height_mm / 1024.0});
  cells_x_ = std::max(1, static_cast<int>(std::ceil(width_mm / cell_mm_)));
  cells_y_ = std::max(1, static_cast<int>(std::ceil(height_mm / cell_mm_)));
  const glm::dvec2 origin{-0.5 * width_mm, -0.5 * height_mm};
  const std::vector<double> upper = cell_upper_bounds(origin);
  double u_max = 0.0;
  for (const double u : upper) u_max = std::max(u_max, u);
  const int n = static_cast<int>(shapes_.size()), block = static_cast<int>(kCrystalBlock), blocks = (n + block - 1) / block;
  std::vector<std::vector<std::pair<int, int>>> found(static_cast<std::size_t>(blocks));  // (cell, crystal)
  tbb::parallel_for(0, blocks, [&](int b) {
    NodeWindow w;
    for (int i = b * block; i < std::min(n, (b + 1) * block); ++i) candidate_cells(i, origin, upper, u_max, w, found[b]);
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
