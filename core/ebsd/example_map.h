#pragma once
// A made-up but rock-like EBSD map, for the example scene (assets/scenes/ebsd_map.json), the
// README and the map benchmark: a calcite-bearing quartzite written as Oxford Channel 5 would
// write it.
//   - grains: a Voronoi tessellation of jittered seeds (mean size grain_um), 85 % quartz, 10 %
//     calcite, 5 % garnet, each grain a uniformly random orientation (Shoemake 1992, "Uniform
//     random rotations", Graphics Gems III);
//   - subgrains: a second, finer tessellation (grain_um / 3) turns each part of a quartz grain by
//     2–5° about a random axis: low-angle boundaries, below the 10° of a grain boundary;
//   - undulose extinction: each quartz grain bent about an in-plane axis, 3° per 100 µm across it;
//   - twins: calcite grains in lamellae 20 µm wide of e-twins, the half-turn about the normal of
//     (01-12) (the library's calcite twin law), on the trace of that plane;
//   - non-indexed points: half of the points within 0.6 steps of a grain boundary, where the
//     patterns of two grains overlap, and 1 % scattered;
//   - orientation noise: 0.1° (a good EBSD system's precision is ~0.5°, Humphreys 2001).
// Deterministic: the same arguments give the same map.
#include <cstdint>

#include "core/ebsd/orientation_map.h"

namespace pmsim {

OrientationMap example_quartzite_map(int columns, int rows, double step_um, double grain_um = 300.0,
                                     std::uint64_t seed = 1);

}  // namespace pmsim
