#include "core/base/asset_locator.h"

#include <cstdlib>

namespace pmsim {

std::string asset_dir() {
  if (const char* env = std::getenv("PMSIM_ASSETS"); env != nullptr && *env != '\0') return env;
  return PMSIM_ASSET_DIR;
}

}  // namespace pmsim
