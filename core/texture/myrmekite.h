#pragma once
// Myrmekite: wart-shaped bulbs of sodic plagioclase pierced by vermicular quartz, standing on a
// plagioclase grain's boundary and bulging into the K-feldspar they replace (Phillips, E.R. (1974),
// Myrmekite — one hundred years later, Lithos 7, 181–194; Vernon, R.H. (2004), A Practical Guide
// to Rock Microstructure, Cambridge, §4.8; Nesse, W.D. (2012), Introduction to Optical Mineralogy,
// 4th ed., quartz and plagioclase). The plagioclase of a bulb is its grain's, continuing its
// lattice and twins; the quartz rods of one grain's bulbs share one orientation, so they go
// extinct together. The rods fan out from the bulb's root toward its rounded front, which they
// meet at a high angle, and wriggle as they go.
//
// A bulb is half an ellipse standing on its root (a point of the grain's boundary): depth along
// the outward direction `out`, half-width across it. The vermicules are the bulb's points whose
// fan angle about a point half a width behind the root, laid out along the arc at mid-depth and
// shifted by a sinusoidal wriggle, falls on a rod: a rod width_mm wide every spacing_mm.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "core/texture/cell_lists.h"

namespace pmsim {

struct MyrmekiteBulb {
  glm::dvec2 root_mm{0.0};
  glm::dvec2 out{1.0, 0.0};  // unit, from the plagioclase into the K-feldspar
  double depth_mm = 0.0, half_width_mm = 0.0;
  int grain = -1;          // the section grain (plagioclase) the bulb belongs to
  std::uint64_t hash = 0;  // the phase of its rods' wriggle
};

struct Vermicules {
  double width_mm = 0.0, spacing_mm = 0.0;  // a rod's width, and rods' spacing along the arc at mid-depth
};

// Whether p lies in bulb b (on its K-feldspar side of the root: depth coordinate ≥ 0).
bool in_bulb(const MyrmekiteBulb& b, const glm::dvec2& p_mm);
// Whether p (in bulb b) lies in one of its quartz rods.
bool in_vermicule(const MyrmekiteBulb& b, const Vermicules& v, const glm::dvec2& p_mm);

// Along the ray from `from` in unit direction `dir`, the distance at which `inside` first turns
// false after having been true: sampled every step_mm out to reach_mm, then bisected to tol_mm.
// Empty when the ray never enters or never leaves within reach.
std::optional<double> ray_exit_mm(const std::function<bool(const glm::dvec2&)>& inside, const glm::dvec2& from,
                                  const glm::dvec2& dir, double reach_mm, double step_mm, double tol_mm);

// The section's bulbs on a uniform grid: each listed in the cells its bounding box touches.
class MyrmekiteBulbs {
 public:
  MyrmekiteBulbs(std::vector<MyrmekiteBulb> bulbs, double width_mm, double height_mm);
  // The first bulb (in the order given) holding p, or −1.
  int at(const glm::dvec2& p_mm) const;
  const MyrmekiteBulb& bulb(int k) const { return bulbs_[static_cast<std::size_t>(k)]; }
  std::size_t size() const { return bulbs_.size(); }
  // How many bulbs belong to section grain `grain` (a grain report asks this of every grain).
  int count_of(int grain) const;

 private:
  std::vector<MyrmekiteBulb> bulbs_;
  std::vector<int> per_grain_;  // bulbs per grain index
  CellLists cells_;
};

}  // namespace pmsim
