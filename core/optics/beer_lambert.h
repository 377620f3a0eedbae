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

// Opaque cut-off for amplitude attenuation e^(−a): at a ≥ 9.2 the amplitude is < 1e-4 and the
// intensity < 1e-8, below anything an image shows (an 8-bit sRGB step near black is 3e-4 in
// linear light, a 16-bit PNG's 1.5e-5), so it is taken as exactly 0. Why not leave e^(−a): 30 µm
// of magnetite at 630 nm (k = 0.148, Querry 1985) is a = 44, intensity e^(−89) ≈ 3e-39, a
// subnormal float once an image holds it (slow arithmetic on x86 without flush-to-zero); and
// between crossed polars a grain passing 1e-10 (magnetite at 440 nm, a = 11) leaves 1e-10 times
// the rounding residue of the polars' cancellation, 1e-42: subnormal again. The threshold keeps
// 30 µm of magnetite (a ≥ 11.1 over 380–780 nm) and ilmenite (a ≥ 24) exactly 0 at every
// wavelength, and touches no coloured silicate of a section (biotite's darkest, 1 % at 400 nm
// through 30 µm, is a = 2.3).
constexpr double kOpaqueAmplitudeExponent = 9.2;
inline double amplitude_attenuation(double exponent) {
  return exponent >= kOpaqueAmplitudeExponent ? 0.0 : std::exp(-exponent);
}

// Propagation phase 2π·O_p/λ (paper §6: dφ = 2π·O_p/λ − δ). O_p in mm, λ in nm.
inline double propagation_phase_rad(double optical_path_mm, double wavelength_nm) {
  return 2.0 * kPi * (optical_path_mm * 1e6 / wavelength_nm);
}

}  // namespace pmsim
