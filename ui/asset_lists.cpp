#include "ui/asset_lists.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace pmsim::ui {

std::vector<std::string> list_asset_stems(const std::string& subdir, const std::string& extension) {
  namespace fs = std::filesystem;
  std::vector<std::string> stems;
  std::error_code ec;
  for (fs::directory_iterator it(fs::path(asset_dir()) / subdir, ec), end; !ec && it != end;
       it.increment(ec)) {
    if (it->is_regular_file(ec) && it->path().extension() == extension)
      stems.push_back(it->path().stem().string());
  }
  std::sort(stems.begin(), stems.end());
  return stems;
}

}  // namespace pmsim::ui
