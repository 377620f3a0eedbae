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
  const glm::dvec2 half{0.5 * width_mm + reach_max, 0.5 * height_mm + reach_max};
  cells_ = CellLists(-half, half, mean);
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const GrainOvergrowth& g = grains_[i];
    const double r = g.form.circumradius_mm;
    if (std::abs(g.nucleus_mm.z) >= r) continue;  // its form misses the plane
    const glm::dvec2 c{g.nucleus_mm.x, g.nucleus_mm.y};
    cells_.add(static_cast<int>(i), c - r, c + r);
  }
}

// The time the overgrowth of grain i reaches p, its faces advancing at one rate from the grain's
// surface: r·(H·gauge − 1); infinite outside its form.
double OvergrowthCement::arrival(std::size_t i, const glm::dvec2& p) const {
  const GrainOvergrowth& g = grains_[i];
  const double s = form_gauge(g, p);
  return s <= 1.0 ? g.radius_mm * (g.habit_scale * s - 1.0) : kInf;
}

int OvergrowthCement::owner(const glm::dvec2& p) const {
  int best = -1;
  double best_t = kInf;
  for (const int i : cells_.at(p)) {  // in index order: ties to the lowest
    const double t = arrival(static_cast<std::size_t>(i), p);
    if (t < best_t) {
      best_t = t;
      best = i;
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
  double least = kInf;
  for (const int i : cells_.at(p)) {
    const GrainOvergrowth& g = grains_[static_cast<std::size_t>(i)];
    // Beyond the registered form (gauge > 1) the grid may not list the grain: not a reach.
    const double s = form_gauge(g, p);
    if (s <= 1.0) least = std::min(least, s * g.habit_scale);
  }
  return least;
}

}  // namespace pmsim
