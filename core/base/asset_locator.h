#pragma once
// Where the data files (assets/: materials, minerals, lenses, scenes, sections) are found.
#include <string>

namespace pmsim {

// $PMSIM_ASSETS when set and non-empty (another copy, a test's scratch folder), else
// <prefix>/share/pmsim beside the running program (core/base/install_layout.h): the installed
// assets, or in a build tree the link to the source's assets/.
std::string asset_dir();

}  // namespace pmsim
