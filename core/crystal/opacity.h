#pragma once
// Opaque minerals (magnetite, ilmenite): crystals whose absorption leaves no visible light through
// a thin section. Their absorption is physical (μ = 4πk/λ from the complex index, the
// "extinction_coefficient_k" form of the mineral files); this names the consequence, for the
// reports that must say "opaque" instead of giving an extinction angle or interference colour.
#include "core/crystal/crystal.h"

namespace pmsim {

// A section transmits less than this along every principal vibration direction at every
// wavelength of 380–780 nm: 1e-4 of the field is below the darkest step of an 8-bit sRGB image
// (code 1 is 3e-4 of white in linear light), so the grain is black in plane and crossed light.
constexpr double kOpaqueTransmittance = 1e-4;

// Whether `thickness_um` of the crystal is opaque in that sense; false for a non-absorbing one.
bool is_opaque(const Crystal& c, double thickness_um = 30.0);

}  // namespace pmsim
