#pragma once
// CIE 1931 2° standard observer x̄(λ), ȳ(λ), z̄(λ) (CIE 15:2004, Table T.4) and the weights that
// turn a spectral transmittance into tristimulus values under an illuminant.
#include <glm/vec3.hpp>

#include "core/spectrum/illuminant.h"

namespace pmsim {

constexpr double kVisibleMinNm = 380.0;
constexpr double kVisibleMaxNm = 780.0;

// (x̄, ȳ, z̄) at wavelength_nm, linear interpolation of the tabulated values.
// Outside 380–780 nm throws std::out_of_range.
glm::dvec3 cie1931_xyz_bar(double wavelength_nm);

// w(λ) = S(λ)·(x̄,ȳ,z̄)(λ) / ∫S·ȳ dλ, so that XYZ = ∫ T(λ)·w(λ) dλ gives Y = 1 for T ≡ 1:
// the exposure reference of the microscope (parallel polars, isotropic layer: Y = 1).
glm::dvec3 observer_weight(Illuminant illum, double wavelength_nm);

// XYZ of the illuminant itself with Y = 1 (the reference white of CIELAB).
glm::dvec3 illuminant_white_xyz(Illuminant illum);

}  // namespace pmsim
