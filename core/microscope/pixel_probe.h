#pragma once
// What the teaching panels show at the cursor: the transmitted spectrum, the retardation and the
// interference order, and which mineral is there. Exact plate Jones matrices (no spectral model).
#include <string>
#include <vector>

#include "core/microscope/scene.h"

namespace pmsim {

struct PixelProbe {
  bool lit = false;                   // false outside the conoscopic disk / the BFP spot
  std::vector<double> wavelength_nm;  // 380, 385, …, 780
  std::vector<double> transmission;   // T(λ) through the whole train (Y = 1 reference)
  double retardation_nm = 0.0;        // Γ at 550 nm (slow − fast), 0 for an empty stage or opaque
  double order = 0.0;                 // Γ / 550 nm
  // An opaque mineral at the probe (magnetite, ilmenite: core/crystal/opacity.h at this thickness):
  // black in every light, so no retardation or interference order can be seen (left 0).
  bool opaque = false;
  double thickness_um = 0.0;
  std::string mineral;  // "quartz", "empty stage", …
};

// (x_frac, y_frac): 0…1 from the left and from the TOP of the image (texture coordinates).
// Throws InputError for an invalid scene.
PixelProbe probe_pixel(const Scene& scene, double x_frac, double y_frac);

}  // namespace pmsim
