#pragma once
// A granoblastic aggregate's grain centres: nuclei relaxed toward a centroidal Voronoi
// tessellation by Lloyd's iteration (Lloyd 1982, IEEE Trans. Inf. Theory 28, 129–137; Du, Faber &
// Gunzburger 1999, SIAM Review 41, 637–676: each step moves every nucleus to the centroid of its
// Voronoi cell).
//
// Why: a monomineralic rock that recrystallised statically (quartzite, marble) coarsens until its
// boundaries' energy is least; grains of one phase then meet in threes at ~120° with nearly equal
// sizes and straight sides (Vernon 2004, A Practical Guide to Rock Microstructure, Cambridge,
// §4.2; Passchier & Trouw 2005, Microtectonics, §3.12 "grain boundary area reduction"). Lloyd's
// iteration lowers the same kind of energy (the cells' second moment) and takes a Poisson–Voronoi
// aggregate, whose angles spread widely, toward a regular foam of equal cells whose sections'
// triple junctions concentrate near 120°.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace pmsim {

struct FoamBox {
  glm::dvec3 lo{0.0}, hi{0.0};  // mm
};

// `count` nuclei, uniform (Poisson) in the box from `seed`, after `iterations` Lloyd steps. The
// cells' centroids are measured on a jittered grid of ~64 points a cell, so a step costs
// ~64·count nearest-nucleus searches. Iterations 0: the Poisson nuclei.
std::vector<glm::dvec3> relaxed_foam_nuclei(const FoamBox& box, std::size_t count, int iterations, std::uint64_t seed);

}  // namespace pmsim
