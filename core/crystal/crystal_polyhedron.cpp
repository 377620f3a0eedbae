#include "core/crystal/crystal_polyhedron.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "core/crystal/mineral_crystallography.h"

namespace pmsim {

namespace {

// Adds the face pair ±n at distance h (n normalised here; a duplicate direction is skipped).
void add_pair(CrystalPolyhedron& p, glm::dvec3 n, double h) {
  n = glm::normalize(n);
  for (const glm::dvec3& m : p.normals)
    if (std::abs(glm::dot(m, n)) > 1.0 - 1e-9) return;
  p.normals.push_back(n);
  p.support_mm.push_back(h);
  p.normals.push_back(-n);
  p.support_mm.push_back(h);
}

glm::dvec3 perpendicular(const glm::dvec3& u) {
  const glm::dvec3 a = std::abs(u.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(u, a));
}

// Prism faces ∥ e: the cleavage planes whose normals are ⟂ e (a prismatic cleavage is a crystal
// form of the zone [uvw]), each at distance h; a square prism when fewer than two show.
void add_prism_sides(CrystalPolyhedron& p, const MineralCrystallography* mc, const glm::dmat3& L,
                     const glm::dvec3& e, double h) {
  std::vector<glm::dvec3> sides;
  if (mc)
    for (const Cleavage& c : mc->cleavage) {
      const glm::dvec3 n = L * plane_normal(mc->cell, c.plane);
      if (std::abs(glm::dot(n, e)) < 0.02) sides.push_back(n);
    }
  if (sides.size() < 2) {
    const glm::dvec3 q = perpendicular(e);
    sides = {q, glm::cross(e, q)};
  }
  for (const glm::dvec3& n : sides) add_pair(p, n - glm::dot(n, e) * e, h);
}

}  // namespace

double default_habit_aspect(const MineralCrystallography* mc) {
  if (!mc || !(mc->habit.elongation || mc->habit.tabular)) return 1.0;
  return mc->habit.tabular ? 5.0 : 3.0;
}

CrystalPolyhedron sphere_polyhedron(double size_mm) {
  CrystalPolyhedron p;
  p.support_mm = {0.5 * size_mm};
  p.circumradius_mm = 0.5 * size_mm;
  return p;
}

double gauge(const CrystalPolyhedron& p, const glm::dvec3& x) {
  if (p.normals.empty()) return glm::length(x) / p.support_mm[0];
  double g = 0.0;
  for (std::size_t f = 0; f < p.normals.size(); ++f) g = std::max(g, glm::dot(p.normals[f], x) / p.support_mm[f]);
  return g;
}

double circumradius_mm(const CrystalPolyhedron& p) {
  if (p.normals.empty()) return p.support_mm[0];
  // Every vertex is the intersection of three face planes inside all the others.
  double r = 0.0;
  const std::size_t n = p.normals.size();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      for (std::size_t c = b + 1; c < n; ++c) {
        const glm::dmat3 m = glm::transpose(glm::dmat3(p.normals[a], p.normals[b], p.normals[c]));
        const double det = glm::determinant(m);
        if (std::abs(det) < 1e-9) continue;
        const glm::dvec3 v = glm::inverse(m) * glm::dvec3(p.support_mm[a], p.support_mm[b], p.support_mm[c]);
        if (gauge(p, v) <= 1.0 + 1e-9) r = std::max(r, glm::length(v));
      }
  return r;
}

CrystalPolyhedron habit_polyhedron(const MineralCrystallography* mc, const glm::dmat3& L, double size_mm,
                                   double aspect) {
  return placed(habit_template(mc, aspect), L, size_mm);
}

CrystalPolyhedron placed(const CrystalPolyhedron& unit, const glm::dmat3& L, double size_mm) {
  CrystalPolyhedron p = unit;
  for (glm::dvec3& n : p.normals) n = L * n;
  for (double& h : p.support_mm) h *= size_mm;
  p.circumradius_mm *= size_mm;
  return p;
}

CrystalPolyhedron habit_template(const MineralCrystallography* mc, double aspect) {
  CrystalPolyhedron p;
  const glm::dmat3 L(1.0);
  const double half = 0.5;
  const bool lattice = mc != nullptr;
  const bool prism = lattice && mc->habit.elongation.has_value();
  const bool plate = lattice && mc->habit.tabular.has_value();
  if (prism && plate) {  // a lath
    const glm::dvec3 e = L * lattice_direction(mc->cell, *mc->habit.elongation);
    const glm::dvec3 n0 = L * plane_normal(mc->cell, *mc->habit.tabular);
    const glm::dvec3 n = glm::normalize(n0 - glm::dot(n0, e) * e);
    add_pair(p, e, half);
    add_pair(p, n, half / aspect);
    add_pair(p, glm::cross(e, n), half / std::sqrt(aspect));
  } else if (prism) {
    const glm::dvec3 e = L * lattice_direction(mc->cell, *mc->habit.elongation);
    add_pair(p, e, half);
    add_prism_sides(p, mc, L, e, half / aspect);
  } else if (plate) {
    const glm::dvec3 n = L * plane_normal(mc->cell, *mc->habit.tabular);
    add_pair(p, n, half / aspect);
    const glm::dvec3 a = perpendicular(n), b = glm::cross(n, a);
    for (int k = 0; k < 3; ++k) {  // hexagon of vertex radius `half`: apothem half·cos 30°
      const double t = k * 3.14159265358979323846 / 3.0;
      add_pair(p, std::cos(t) * a + std::sin(t) * b, half * std::sqrt(3.0) / 2.0);
    }
  } else if (lattice && mc->system == CrystalSystem::Cubic) {
    for (const glm::dvec3 d : {glm::dvec3(1, 1, 0), glm::dvec3(1, -1, 0), glm::dvec3(1, 0, 1), glm::dvec3(1, 0, -1),
                               glm::dvec3(0, 1, 1), glm::dvec3(0, 1, -1)})
      add_pair(p, L * d, half / std::sqrt(2.0));  // {110}: vertices at `half` along <100>
  } else {
    const glm::dmat3 R = lattice ? L * glm::dmat3(plane_normal(mc->cell, {1, 0, 0}), plane_normal(mc->cell, {0, 1, 0}),
                                                  plane_normal(mc->cell, {0, 0, 1}))
                                 : L;
    for (int k = 0; k < 3; ++k) add_pair(p, R[k], half / std::sqrt(3.0) * 1.25);
    for (int k = 0; k < 3; ++k) add_pair(p, R[k] + R[(k + 1) % 3], half * 0.85);
  }
  p.circumradius_mm = circumradius_mm(p);
  return p;
}

}  // namespace pmsim
