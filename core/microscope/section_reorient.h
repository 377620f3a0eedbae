#pragma once
// sample.orientation_seed: a new specimen of the same rock. Every grain of a thin-section file
// keeps its mineral, place, size, twin and zones, and is given a new crystal orientation drawn
// uniformly over the rotations from the seed; its outline follows, as the section of its habit
// ellipsoid in the new orientation (docs/sections.md). So each student of a class gets a section
// with the rock's texture and mode but their own extinction angles, colours and figures.
#include <array>
#include <cstdint>

#include <nlohmann/json.hpp>

namespace pmsim {

// Bunge (φ1, Φ, φ2) in degrees of a rotation uniform over SO(3): φ1 and φ2 uniform in [0, 360),
// cos Φ uniform in [−1, 1] (the Haar measure in Euler angles, dg ∝ sin Φ dφ1 dΦ dφ2; Bunge 1982,
// Texture Analysis in Materials Science, §2.2). Depends on (seed, grain) only.
std::array<double, 3> uniform_euler_deg(std::uint64_t seed, std::uint64_t grain);

// Rewrites a parsed section file's grains in place: euler_deg from uniform_euler_deg(seed, index),
// the legacy orientation keys (optic_axis, x_axis, z_axis, elongation_deg) removed.
void reorient_section_grains(nlohmann::json& section, std::uint64_t seed);

}  // namespace pmsim
