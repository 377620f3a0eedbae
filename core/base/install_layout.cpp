#include "core/base/install_layout.h"

#include <stdexcept>
#include <system_error>

namespace pmsim {

std::filesystem::path executable_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the running program (/proc/self/exe): " + ec.message());
  return exe.parent_path();
}

std::filesystem::path install_prefix() { return executable_dir().parent_path(); }

}  // namespace pmsim
