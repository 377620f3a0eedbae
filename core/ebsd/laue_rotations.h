#pragma once
// The proper rotations of a Laue class (its rotation subgroup: 1, 2, 222, 4, 422, 3, 32, 6, 622,
// 23, 432 for -1 … m-3m), written in pmsim's crystal Cartesian frame (core/crystal/lattice.h:
// e1 ∥ a, e3 ∥ c*; so e2 ∥ b for a monoclinic cell with b unique, and e3 ∥ c for tetragonal,
// hexagonal and trigonal cells). Two orientations g and g·s (s one of these) are the same crystal:
// misorientations are the smallest angle over them.
//   2/m: the 2-fold along b (e2), the b-unique setting of mineral monoclinic cells;
//   -3m: the 2-folds along the a axes (e1 and its 120° turns), the setting of the trigonal
//        minerals of the library (quartz 32, calcite -3 2/m: International Tables vol. A,
//        point groups 32 and -3m with 2-fold axes along [100], [010], [-1-10]).
#include <string_view>
#include <vector>

#include <glm/gtc/quaternion.hpp>

namespace pmsim {

// Unit quaternions (w ≥ 0) of the group; empty for an unknown symbol. The identity first.
std::vector<glm::dquat> laue_rotations(std::string_view laue_symbol);

}  // namespace pmsim
