#pragma once
// Detrital grains packed as a sand: a sandstone's framework is a pile of touching grains, flattened
// against each other by compaction (long contacts) where they meet (Pettijohn, Potter & Siever
// 1987, Sand and Sandstone, ch. 3 "packing"; Taylor, J.M. 1950, AAPG Bull. 34, 701–716, the
// point, long, concavo-convex and sutured contacts), not a Poisson scatter of balls that sink
// into one another and leave empty patches.
//
// Balls (centres, radii) are pushed apart until no two overlap by more than max_overlap of the
// sum of their radii: Jacobi steps, each moving both balls of an offending pair half the excess
// apart. The moves are horizontal (the section plane), so every ball stays within the slab of
// heights it was drawn in (rock_growth.h draws only crystals that cut the section), and stay in
// the box the centres were drawn in, taken as periodic (free edges would let the pile spread and
// thin out; walls would pile it against them and leave the middle loose).
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace pmsim {

struct PackingResult {
  int steps = 0;
  double worst_overlap = 0.0;  // the largest remaining (r_i + r_j − d) / (r_i + r_j), after the last step
};

PackingResult pack_balls(std::vector<glm::dvec3>& centres_mm, const std::vector<double>& radii_mm,
                         const glm::dvec2& box_lo_mm, const glm::dvec2& box_hi_mm, double max_overlap, int max_steps);

}  // namespace pmsim
