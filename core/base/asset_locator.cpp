#include "core/base/asset_locator.h"

#include <cstdlib>

#include "core/base/install_layout.h"

namespace pmsim {

std::string asset_dir() {
  if (const char* env = std::getenv("PMSIM_ASSETS"); env != nullptr && *env != '\0') return env;
  return (install_prefix() / "share" / "pmsim").string();
}

}  // namespace pmsim
