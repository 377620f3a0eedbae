#include "core/base/version.h"

namespace pmsim {

std::string pmsim_version() { return PMSIM_VERSION; }

std::string pmsim_software_name() { return std::string("pmsim ") + PMSIM_VERSION; }

}  // namespace pmsim
