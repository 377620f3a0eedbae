#pragma once
// The bench rows of the refracting specimen (issue 12): a grain mount of garnet in a liquid of
// 1.54 at focus_um = 5, plane light, size² pixels — the time to the first progressive image and to
// 64 samples a pixel, each with its mean CIEDE2000 against an independent 256-sample reference
// (another seed), and the reference's own convergence (its 128-sample image against it).
#include <ostream>
#include <vector>

#include "core/bench/bench_run.h"

namespace pmsim {

std::vector<BenchRow> grain_mount_bench_rows(int size, std::ostream& log);
// Crossed polars on a calcite grain mount in 1.54 (the polarization-exact tracer, 32 bands), at
// min(size, 256)²: first pass and 64 samples a pixel against a 1024-sample reference (another seed).
std::vector<BenchRow> crossed_polar_grain_mount_bench_rows(int size, std::ostream& log);

}  // namespace pmsim
