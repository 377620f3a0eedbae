#pragma once
// An EBSD map file by its extension: .ctf (Oxford Channel 5, core/ebsd/ctf_reader.h) or .ang
// (EDAX/TSL, core/ebsd/ang_reader.h), case-insensitive. Any other extension is an InputError.
#include <string>

#include "core/ebsd/orientation_map.h"

namespace pmsim {

bool is_orientation_map_path(const std::string& path);  // ends in .ctf or .ang
OrientationMap read_orientation_map(const std::string& path, const EbsdReadOptions& options = {});

}  // namespace pmsim
