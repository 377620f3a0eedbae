#pragma once
// Writes an OrientationMap as a vendor file in the layout the readers read (core/ebsd/ctf_reader.h,
// ang_reader.h): for made-up maps (the load benchmark, examples the project generates). The map's
// angles are written as they are (in the map's vendor frames; writing a map read from the other
// vendor's file does not convert them). Non-indexed points: ctf phase 0 with zero angles; ang
// angles 4π, CI −1 and, in a file of several phases, phase 0 (the vendors' own marks).
// Throws std::runtime_error when the file cannot be written.
#include <string>

#include "core/ebsd/orientation_map.h"

namespace pmsim {

void write_ctf(const OrientationMap& m, const std::string& path);
void write_ang(const OrientationMap& m, const std::string& path);

}  // namespace pmsim
