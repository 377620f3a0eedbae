#pragma once
// sample.orientation_seed: a new specimen of the same rock. Every grain of a thin-section file
// keeps its mineral, place, size, twin and zones, and is given a new crystal orientation drawn
// uniformly over the rotations from the seed; its outline follows, as the section of its habit
// ellipsoid in the new orientation (docs/sections.md). So each student of a class gets a section
// with the rock's texture and mode but their own extinction angles, colours and figures.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "core/crystal/uniform_orientation.h"

namespace pmsim {

// Rewrites a parsed section file's grains in place: euler_deg from uniform_euler_deg(seed, index),
// the legacy orientation keys (optic_axis, x_axis, z_axis, elongation_deg) removed.
void reorient_section_grains(nlohmann::json& section, std::uint64_t seed);
// The same for one grain object, the index-th of its file (counting only objects).
void reorient_section_grain(nlohmann::json& grain, std::uint64_t seed, std::uint64_t index);

}  // namespace pmsim
