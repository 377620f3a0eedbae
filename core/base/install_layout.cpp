#include "core/base/install_layout.h"

#include <stdexcept>
#include <system_error>

namespace pmsim {

std::filesystem::path executable_dir() {
  // Read once: the program does not move while it runs, and asset_dir() asks on every load.
  static const std::filesystem::path dir = [] {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find the running program (/proc/self/exe): " + ec.message());
    return exe.parent_path();
  }();
  return dir;
}

std::filesystem::path install_prefix() { return executable_dir().parent_path(); }

}  // namespace pmsim
