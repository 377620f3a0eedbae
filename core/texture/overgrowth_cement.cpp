#include "core/texture/overgrowth_cement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/crystal/lattice.h"
#include "core/crystal/mineral_crystallography.h"

namespace pmsim {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNoCementScale = 1e-3;

void add_face(CrystalPolyhedron& p, const glm::dvec3& n) {
  p.normals.push_back(glm::normalize(n));
  p.support_mm.push_back(1.0);
}

// The gauge of o's form at section point p (1 on its faces), about the ball's centre.
double form_gauge(const GrainOvergrowth& o, const glm::dvec2& p) {
  return gauge(o.form, {p.x - o.nucleus_mm.x, p.y - o.nucleus_mm.y, -o.nucleus_mm.z});
}
}  // namespace

CrystalPolyhedron overgrowth_unit_form(const MineralCrystallography& mc) {
  CrystalPolyhedron p;
  if (mc.system == CrystalSystem::Hexagonal || mc.system == CrystalSystem::Trigonal) {
    // (hkl) in the hexagonal setting, i = −(h + k) dropped: the six prism faces {10-10} and the
    // twelve faces of {10-11} and {01-11} (l = ±1), every one at distance 1.
    const MillerIndices prism[] = {{1, 0, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {1, -1, 0}};
    for (const MillerIndices& m : prism) {
      add_face(p, plane_normal(mc.cell, m));
      add_face(p, plane_normal(mc.cell, {m.h, m.k, 1}));
      add_face(p, plane_normal(mc.cell, {m.h, m.k, -1}));
    }
    p.circumradius_mm = circumradius_mm(p);
    return p;
  }
  p = habit_template(&mc, default_habit_aspect(&mc));
  const double h = p.normals.empty() ? p.support_mm[0] : *std::min_element(p.support_mm.begin(), p.support_mm.end());
  return placed(p, glm::dmat3(1.0), 1.0 / h);
}

CrystalPolyhedron overgrowth_form(const CrystalPolyhedron& unit, const glm::dmat3& L, double radius_mm,
                                  double habit_scale) {
  return placed(unit, L, radius_mm * habit_scale);
}

double overgrowth_reach(const GrainOvergrowth& o, const glm::dvec2& p) { return form_gauge(o, p) * o.habit_scale; }

double overgrowth_scale_for(std::vector<double> reach, std::size_t total, double cement) {
  const auto k = static_cast<std::size_t>(std::llround(cement * static_cast<double>(total)));
  const auto finite = static_cast<std::size_t>(std::count_if(reach.begin(), reach.end(), [](double r) { return r < kInf; }));
  if (k > finite)
    throw std::invalid_argument("the pores hold " + std::to_string(double(finite) / double(std::max<std::size_t>(total, 1))) +
                                " of the section within the overgrowths' reach, less than the cement's " +
                                std::to_string(cement));
  // Less cement than one point: a scale no point reaches (a form shrunk inside its grain), yet a
  // valid one for the section file's reader, which takes (0, 3].
  if (k == 0) return kNoCementScale;
  std::nth_element(reach.begin(), reach.begin() + std::ptrdiff_t(k - 1), reach.end());
  return reach[k - 1];
}

OvergrowthCement::OvergrowthCement(std::vector<GrainOvergrowth> grains, double width_mm, double height_mm)
    : grains_(std::move(grains)) {
  if (grains_.empty()) return;
  // A form's section lies within its circumradius of the nucleus: register each grain in the
  // cells that disc's bounding square meets. Cells about the mean reach: a few grains each.
  double mean = 0.0, reach_max = 0.0;
  for (const GrainOvergrowth& g : grains_) {
    mean += g.form.circumradius_mm;
    reach_max = std::max(reach_max, g.form.circumradius_mm);
  }
  mean /= static_cast<double>(grains_.size());
  x0_ = -0.5 * width_mm - reach_max;
  y0_ = -0.5 * height_mm - reach_max;
  cell_mm_ = std::max({mean, (width_mm + 2.0 * reach_max) / 2048.0, (height_mm + 2.0 * reach_max) / 2048.0});
  cells_x_ = std::max(1, static_cast<int>(std::ceil((width_mm + 2.0 * reach_max) / cell_mm_)));
  cells_y_ = std::max(1, static_cast<int>(std::ceil((height_mm + 2.0 * reach_max) / cell_mm_)));
  std::vector<std::vector<int>> lists(static_cast<std::size_t>(cells_x_) * cells_y_);
  const auto cell = [&](double v, double v0, int n) { return std::clamp(static_cast<int>(std::floor((v - v0) / cell_mm_)), 0, n - 1); };
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const GrainOvergrowth& g = grains_[i];
    const double r = g.form.circumradius_mm;
    if (std::abs(g.nucleus_mm.z) >= r) continue;  // its form misses the plane
    for (int cy = cell(g.nucleus_mm.y - r, y0_, cells_y_); cy <= cell(g.nucleus_mm.y + r, y0_, cells_y_); ++cy)
      for (int cx = cell(g.nucleus_mm.x - r, x0_, cells_x_); cx <= cell(g.nucleus_mm.x + r, x0_, cells_x_); ++cx)
        lists[static_cast<std::size_t>(cy) * cells_x_ + cx].push_back(static_cast<int>(i));
  }
  cell_start_.assign(1, 0);
  for (const auto& l : lists) {
    cell_grains_.insert(cell_grains_.end(), l.begin(), l.end());
    cell_start_.push_back(static_cast<int>(cell_grains_.size()));
  }
}

// The time the overgrowth of grain i reaches p, its faces advancing at one rate from the grain's
// surface: r·(H·gauge − 1); infinite outside its form.
double OvergrowthCement::arrival(std::size_t i, const glm::dvec2& p) const {
  const GrainOvergrowth& g = grains_[i];
  const double s = form_gauge(g, p);
  return s <= 1.0 ? g.radius_mm * (g.habit_scale * s - 1.0) : kInf;
}

int OvergrowthCement::cell(const glm::dvec2& p) const {
  if (cell_start_.empty()) return -1;
  const double fx = std::floor((p.x - x0_) / cell_mm_), fy = std::floor((p.y - y0_) / cell_mm_);
  if (!(fx >= 0.0 && fy >= 0.0 && fx < cells_x_ && fy < cells_y_)) return -1;
  return static_cast<int>(fy) * cells_x_ + static_cast<int>(fx);
}

int OvergrowthCement::owner(const glm::dvec2& p) const {
  const int c = cell(p);
  if (c < 0) return -1;
  int best = -1;
  double best_t = kInf;
  for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {  // in index order: ties to the lowest
    const double t = arrival(static_cast<std::size_t>(cell_grains_[k]), p);
    if (t < best_t) {
      best_t = t;
      best = cell_grains_[k];
    }
  }
  return best;
}

int OvergrowthCement::owner_exhaustive(const glm::dvec2& p) const {
  int best = -1;
  double best_t = kInf;
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const double t = arrival(i, p);
    if (t < best_t) {
      best_t = t;
      best = static_cast<int>(i);
    }
  }
  return best;
}

double OvergrowthCement::least_reach(const glm::dvec2& p) const {
  const int c = cell(p);
  if (c < 0) return kInf;
  double least = kInf;
  for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
    const GrainOvergrowth& g = grains_[static_cast<std::size_t>(cell_grains_[k])];
    // Beyond the registered form (gauge > 1) the grid may not list the grain: not a reach.
    const double s = form_gauge(g, p);
    if (s <= 1.0) least = std::min(least, s * g.habit_scale);
  }
  return least;
}

}  // namespace pmsim
