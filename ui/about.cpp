#include "ui/about.h"

#include "core/base/asset_locator.h"
#include "core/base/install_layout.h"
#include "core/base/version.h"

namespace pmsim::ui {

std::vector<std::string> about_lines() {
  return {
      pmsim_software_name(),
      "A polarizing-microscope simulator: a spectral, polarization-aware ray tracer behind the "
      "controls of a petrographic microscope.",
      "Lens model: V. A. Debelov, K. G. Kushner, L. F. Vasilyeva, \"Lens for a computer model of a "
      "polarizing microscope\".",
      "Data (materials, minerals, scenes): " + asset_dir(),
      "Documentation: " + (install_prefix() / "share" / "doc" / "pmsim").string() +
          " (installed) or docs/ in the source tree",
  };
}

}  // namespace pmsim::ui
