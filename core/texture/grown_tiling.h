#pragma once
// Which grown crystal owns a point of the section plane: the one whose faces reach it first.
// Crystals nucleate at time `from` and their faces advance at a constant rate until `to`, when
// they have their free-growth shape (constant habit, the growth of Marsh 1988's CSD theory). The
// owner of a point is the crystal of least arrival time: a Johnson–Mehl tessellation with
// polyhedral growth (Johnson & Mehl 1939, Trans. AIME 135, 416; the crystallisation model of
// Hersum & Marsh 2006, J. Volcanol. Geotherm. Res. 154, 34–47). Early crystals keep their faces,
// later ones fill what is left between them; a late, fast crystal encloses earlier small ones
// (ophitic and poikilitic texture).
//
// With a matrix (a volcanic rock's glass) crystals stop at `to` and a point no crystal reaches
// belongs to the matrix; without one the crystals grow on until the rock is full.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/crystal/crystal_polyhedron.h"

namespace pmsim {

struct GrainGrowth {
  glm::dvec3 nucleus_mm{0.0};  // z: height above the section plane
  double from = 0.0, to = 1.0;
  CrystalPolyhedron shape;  // at time `to`
  // A porphyroblast grows in a rock that is already crystalline, replacing the matrix grains in
  // its way (Passchier & Trouw 2005, Microtectonics, §7.2; Vernon 2004, A Practical Guide to Rock
  // Microstructure, §5.2): inside its free-growth shape it owns every point that no other
  // overgrowing crystal reaches first, whenever the matrix crystals got there.
  bool overgrows = false;
};

// Growth fraction s at which the crystal's faces reach section point p (the gauge of its shape
// about the nucleus: s ≤ 1 while it grows); the time they get there is from + s·(to − from).
double growth_fraction(const GrainGrowth& g, const glm::dvec2& p_mm);

// The time that decides ownership at growth fraction s: from + s·(to − from), less a lead that
// puts an overgrowing crystal's free-growth shape (s ≤ 1) before every crystal that does not
// overgrow. Nondecreasing in s, so quasi-convex in p (a gauge is convex): over a cell its
// maximum is at a corner, as the lookup grid's bounds need.
double arrival_time(const GrainGrowth& g, double s);

// A crystal given as a unit habit template placed by a rotation and a size: placed(*unit, L,
// size_mm) of crystal_polyhedron.h, bit for bit, without a heap-allocated copy per crystal (a
// 20 × 15 mm andesite draws 1.7 million).
struct PlacedGrowth {
  glm::dvec3 nucleus_mm{0.0};
  double from = 0.0, to = 1.0;
  const CrystalPolyhedron* unit = nullptr;
  glm::dmat3 L{1.0};
  double size_mm = 1.0;
  bool overgrows = false;
};

class GrownTiling {
 public:
  // Builds the lookup grid over the section's extent (centred on the origin).
  GrownTiling(const std::vector<GrainGrowth>& crystals, bool capped, double width_mm, double height_mm);
  // The same from n crystals held elsewhere (a section's grains: no copies).
  GrownTiling(std::size_t n, const std::function<const GrainGrowth&(std::size_t)>& crystal, bool capped,
              double width_mm, double height_mm);
  // The same from n crystals placed from templates (crystal(i) is called once per crystal, from
  // several threads).
  GrownTiling(std::size_t n, const std::function<PlacedGrowth(std::size_t)>& crystal, bool capped, double width_mm,
              double height_mm);
  GrownTiling() = default;

  // The crystal owning section point p (an index into crystals), or −1 where none reaches it
  // (only with a matrix). Equal to owner_exhaustive everywhere, ties included (lowest index wins).
  int owner(const glm::dvec2& p_mm) const;
  int owner_exhaustive(const glm::dvec2& p_mm) const;
  std::size_t size() const { return shapes_.size(); }
  const glm::dvec3& nucleus_mm(std::size_t i) const { return shapes_[i].nucleus_mm; }
  bool capped() const { return capped_; }

  // A crystal as the lookup needs it, its faces in faces_ (normal, support). Habit polyhedra have
  // their faces in opposite pairs of one support (crystal_polyhedron.cpp): only the first of each
  // pair is kept, and the gauge takes |n·x|/h, the same number as the larger of n·x/h and −n·x/h.
  struct Shape {
    glm::dvec3 nucleus_mm{0.0};
    double from = 0.0, span = 1.0;  // span: to − from
    double circumradius_mm = 0.0, h_min = 0.0, ball_mm = 0.0;  // ball_mm: a ball's radius (no faces)
    std::uint32_t first_face = 0;
    std::uint16_t faces = 0;
    bool paired = false, overgrows = false;
  };

 private:
  struct NodeWindow;
  void build();
  double fraction(int i, const glm::dvec2& p) const;
  bool beyond(int i, const glm::dvec2& p) const;
  double arrival_at(int i, double s) const;
  double arrival(int i, const glm::dvec2& p) const;
  void window(int i, double s_reach, const glm::dvec2& origin, NodeWindow& w) const;
  std::vector<double> cell_upper_bounds(const glm::dvec2& origin) const;
  void candidate_cells(int i, const glm::dvec2& origin, const std::vector<double>& upper, double u_max, NodeWindow& w,
                       std::vector<std::pair<int, int>>& out) const;

  std::vector<Shape> shapes_;
  std::vector<glm::dvec4> faces_;
  bool capped_ = false;
  double width_mm_ = 0.0, height_mm_ = 0.0, cell_mm_ = 1.0;
  int cells_x_ = 0, cells_y_ = 0;
  std::vector<int> cell_start_, cell_crystals_;
};

}  // namespace pmsim
