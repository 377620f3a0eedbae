#pragma once
// The bench rows of crossed polars on a grain mount (issue 12, the polarization-exact specimen
// tracer): calcite fragments in a liquid of 1.54, polarizer 0°, analyzer 90°, at min(size, 256)²
// pixels — the first progressive image (8 of the 32 bands) and 64 samples a pixel, each with its
// mean CIEDE2000 against an independent 1024-sample reference (another seed), and the reference's
// own convergence (its 512-sample image against it).
#include <ostream>
#include <vector>

#include "core/bench/bench_run.h"

namespace pmsim {

std::vector<BenchRow> crossed_polar_grain_bench_rows(int size, std::ostream& log);

}  // namespace pmsim
