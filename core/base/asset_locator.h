#pragma once
// Where the data files (assets/: materials, minerals, lenses, scenes, sections) are found.
#include <string>

namespace pmsim {

// $PMSIM_ASSETS when set and non-empty (an installed copy, a test's scratch folder), else the
// source tree's assets folder compiled in as PMSIM_ASSET_DIR.
std::string asset_dir();

}  // namespace pmsim
