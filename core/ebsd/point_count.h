#pragma once
// How many points a map header promises and how many the file held: the readers refuse absurd
// promises before allocating, and a file holding fewer points than promised (a map cropped in a
// text editor, a download cut short) loads what it holds, the rest non-indexed, with a warning
// that gives both counts.
#include <cstddef>

#include "core/ebsd/map_text.h"
#include "core/ebsd/orientation_map.h"

namespace pmsim {

// 10⁸ points is 1.3 GB of map (13 bytes a point) — beyond any EBSD map we know of (the largest
// published maps are a few 10⁷ points); a larger promise is a header typo.
inline constexpr double kMaxMapPoints = 1e8;

// InputError (at the current line of `t`) unless 1 ≤ promised ≤ kMaxMapPoints.
void check_point_count(const MapText& t, double promised);

// Records points_in_file and, when it is short of the grid, the warning (the points past it are
// already non-indexed: OrientationMap::allocate_points).
void finish_point_count(OrientationMap& m, std::size_t held, const char* header_terms);

}  // namespace pmsim
