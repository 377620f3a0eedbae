#pragma once
// The bench rows of the refracting specimen (issue 12): a grain mount of garnet in a liquid of
// 1.54 at focus_um = 5, plane light, size² pixels, rendered as the product renders it — the
// preview, the first full pass, 64 paths a pixel, and the image that stops at a split-half
// estimate below 1 or at 256 paths — each with its time
// (wall and CPU) and mean CIEDE2000 against an independent 1024-path reference (another seed;
// its own split-half estimate on its row).
#include <ostream>
#include <string>
#include <vector>

#include "core/bench/bench_run.h"

namespace pmsim {

std::vector<BenchRow> grain_mount_bench_rows(int size, std::ostream& log);
// Crossed polars on a grain mount (the polarization-exact tracer): calcite fragments in a liquid
// of 1.54, polarizer 0°, analyzer 90°, at min(size, 256)² pixels, the same rows as above.
std::vector<BenchRow> crossed_polar_grain_bench_rows(int size, std::ostream& log);
// The granite thin section at 10× in plane light (analyzer out, optics.relief on): the slab traced
// forward from the condenser as the product does (forward_plane_light.h), against a forward
// reference of 256 traces a pixel; its build time reported alongside (not in the rows' times: a
// polarizer or focus change reuses the cached slab).
std::vector<BenchRow> section_relief_bench_rows(int size, std::ostream& log);
// The same granite slab between crossed polars (polarizer 0°, analyzer 90°: forward, 32 bands on
// a subgrid, 3 traces a pixel a pass), at min(size, 256)² pixels so that its 256-trace reference
// stays near a minute.
std::vector<BenchRow> section_crossed_bench_rows(int size, std::ostream& log);
// The rows' strategy names are "<polars>-<suffix>", polars "plane-light" or "crossed-polars".
const std::vector<std::string>& specimen_bench_strategy_suffixes();

}  // namespace pmsim
