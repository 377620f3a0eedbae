#pragma once
// What the sample and file pickers offer: files found in the assets folder (environment variable
// PMSIM_ASSETS, else the source tree's assets/).
#include <string>
#include <vector>

#include "core/base/asset_locator.h"  // pmsim::asset_dir()

namespace pmsim::ui {

// Stems of the files in assets/<subdir> ending in `extension`, sorted; empty if no such folder.
std::vector<std::string> list_asset_stems(const std::string& subdir, const std::string& extension);

}  // namespace pmsim::ui
