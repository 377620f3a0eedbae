#pragma once
// Crystal orientations drawn uniformly over the rotations, reproducibly from a seed: the new
// specimens of sample.orientation_seed (core/microscope/section_reorient.h) and the grown rocks of
// sample.seed (core/texture) draw them the same way.
#include <array>
#include <cstdint>

namespace pmsim {

// Bunge (φ1, Φ, φ2) in degrees of a rotation uniform over SO(3): φ1 and φ2 uniform in [0, 360),
// cos Φ uniform in [−1, 1] (the Haar measure in Euler angles, dg ∝ sin Φ dφ1 dΦ dφ2; Bunge 1982,
// Texture Analysis in Materials Science, §2.2). Depends on (seed, grain) only.
std::array<double, 3> uniform_euler_deg(std::uint64_t seed, std::uint64_t grain);

}  // namespace pmsim
