#pragma once
// Propagation inside a homogeneous isotropic medium (paper §6): optical path and absorption.
#include <cmath>

#include "core/base/units.h"

namespace pmsim {

// Optical path O_p = n·S (paper §6; Born & Wolf §3.3.1).
inline double optical_path_mm(double n, double length_mm) { return n * length_mm; }

// Beer–Lambert–Bouguer law I(x) = I0·e^(−μx) (paper §6): fraction of intensity left after x.
inline double beer_lambert_transmittance(double attenuation_per_mm, double length_mm) {
  return attenuation_per_mm > 0.0 ? std::exp(-attenuation_per_mm * length_mm) : 1.0;
}

// Propagation phase 2π·O_p/λ (paper §6: dφ = 2π·O_p/λ − δ). O_p in mm, λ in nm.
inline double propagation_phase_rad(double optical_path_mm, double wavelength_nm) {
  return 2.0 * kPi * (optical_path_mm * 1e6 / wavelength_nm);
}

}  // namespace pmsim
