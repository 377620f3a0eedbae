#pragma once
// The bench rows of the refracting specimen (issue 12): a grain mount of garnet in a liquid of
// 1.54 at focus_um = 5, plane light, size² pixels — the time to the first progressive image and to
// 64 samples a pixel and to the first image within mean ΔE00 1, each with its mean CIEDE2000 against an independent 256-sample reference
// (another seed), and the reference's own convergence (its 128-sample image against it).
#include <ostream>
#include <vector>

#include "core/bench/bench_run.h"

namespace pmsim {

std::vector<BenchRow> grain_mount_bench_rows(int size, std::ostream& log);
// The granite thin section at 10× in plane light (analyzer out, optics.relief on): the slab traced
// as above, its build time reported alongside (not in the rows' times: a polarizer or focus
// change reuses the cached slab).
std::vector<BenchRow> section_relief_bench_rows(int size, std::ostream& log);

}  // namespace pmsim
