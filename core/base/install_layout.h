#pragma once
// Where a pmsim program finds its files: relative to its own executable, so that an installed copy
// runs from any prefix and no absolute path of the checkout is compiled into a program.
//   installed:  <prefix>/bin/<program>, <prefix>/share/pmsim (assets), <prefix>/lib/pmsim/modules
//   build tree: build/{app,tests,fuzz}/<program>, build/share/pmsim (a link to the source's
//               assets/, made at configure time), build/lib/pmsim/modules (the OpenImageIO module)
#include <filesystem>

namespace pmsim {

// The folder holding the running executable (/proc/self/exe, symlinks resolved).
std::filesystem::path executable_dir();

// The executable's folder's parent: the installation prefix, or the build tree.
std::filesystem::path install_prefix();

}  // namespace pmsim
