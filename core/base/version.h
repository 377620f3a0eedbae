#pragma once
// pmsim's version: the CMake project version (CMakeLists.txt, the one place it is set), reported by
// every program's --version, the app's About box and the metadata of every image written.
#include <string>

namespace pmsim {

std::string pmsim_version();

// "pmsim <version>": the Software tag of written images.
std::string pmsim_software_name();

}  // namespace pmsim
