#pragma once
// Syntaxial overgrowth cement: quartz that a sandstone's pore water precipitated on its detrital
// quartz grains, in lattice continuity with each grain (it extinguishes with it), growing toward
// the crystal's own euhedral form and leaving the grain's rounded surface inside, marked by a
// "dust line" of the clay and fluid that coated it (McBride 1989, Earth-Sci. Rev. 26, 69–112,
// "Quartz cement in sandstones: a review"; Tucker 2001, Sedimentary Petrology, 3rd ed., §2.9.1;
// Adams, MacKenzie & Guilford 1984, Atlas of Sedimentary Rocks under the Microscope, the quartz
// arenites' overgrowths).
//
// Each overgrowth is the grain's habit polyhedron in its lattice orientation, centred on the
// detrital ball and scaled so that its smallest face support is habit_scale × the ball's radius:
// below 1 the faces cut into the ball and only the form's edges and corners stand out into the
// pores as facets (an early, partial cement); at 1 the form circumscribes the ball. A pore point
// inside several grains' forms goes to the face that got there first, all faces advancing at one
// rate from their grain's surface: arrival r·(H·gauge − 1), the compromise boundaries where two
// overgrowths meet. A point a detrital grain owns is never cement.
#include <cstddef>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/crystal_polyhedron.h"
#include "core/texture/cell_lists.h"

namespace pmsim {

struct GrainOvergrowth {
  glm::dvec3 nucleus_mm{0.0};  // the detrital ball's centre (z: height above the section plane)
  double radius_mm = 0.0;      // the detrital ball's radius
  double habit_scale = 1.0;    // the form's inradius over radius_mm
  CrystalPolyhedron form;      // the euhedral form, about the centre (gauge ≤ 1 inside)
};

// The euhedral form an overgrowth grows toward, in the crystal frame, every face at support 1
// (inradius 1: at habit_scale 1 each face touches the detrital ball). A hexagonal or trigonal
// mineral (quartz) takes the hexagonal prism m{10-10} and the two rhombohedra r{10-11} and
// z{01-11}, together the dipyramid (Deer, Howie & Zussman 2013, quartz: the common habit of
// euhedral quartz and of its overgrowths' faces); other minerals their habit polyhedron
// (crystal_polyhedron.h) scaled to inradius 1.
CrystalPolyhedron overgrowth_unit_form(const MineralCrystallography& mc);

// The form of an overgrowth: `unit` (overgrowth_unit_form) turned by the lattice frame L and
// scaled to inradius habit_scale × radius_mm.
CrystalPolyhedron overgrowth_form(const CrystalPolyhedron& unit, const glm::dmat3& L, double radius_mm,
                                  double habit_scale);

// The smallest habit_scale at which an overgrowth's form reaches section point p (its gauge at
// scale 1): p is cement of a form of scale H exactly when this is ≤ H.
double overgrowth_reach(const GrainOvergrowth& o, const glm::dvec2& p_mm);

// The habit_scale at which overgrowths of one scale fill `cement` of the points whose reaches are
// `reach` (a pore raster's least reach over the grains, one value a point) and `total` the points
// of the whole raster: the quantile of the reaches at cement·total (rounded to whole points; under
// one point, 10⁻³: a form inside its grain, no cement). Infinite reaches (points no form of any
// scale reaches) are never cement. Throws std::invalid_argument if the pores cannot hold that
// much cement.
double overgrowth_scale_for(std::vector<double> reach, std::size_t total, double cement);

class OvergrowthCement {
 public:
  OvergrowthCement(std::vector<GrainOvergrowth> grains, double width_mm, double height_mm);
  OvergrowthCement() = default;
  // The overgrowth (index into the grains given) that fills pore point p, or −1 (open pore). The
  // caller asks only for points no detrital grain owns. Equal to owner_exhaustive, ties included
  // (lowest index wins).
  int owner(const glm::dvec2& p_mm) const;
  int owner_exhaustive(const glm::dvec2& p_mm) const;
  // The least overgrowth_reach over every grain at p (what overgrowth_scale_for calibrates on).
  double least_reach(const glm::dvec2& p_mm) const;
  std::size_t size() const { return grains_.size(); }
  const GrainOvergrowth& grain(std::size_t i) const { return grains_[i]; }

 private:
  double arrival(std::size_t i, const glm::dvec2& p) const;
  std::vector<GrainOvergrowth> grains_;
  // A grid over the section; per cell the overgrowths whose forms' section discs reach it.
  CellLists cells_;
};

}  // namespace pmsim
