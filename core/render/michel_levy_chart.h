#pragma once
// The Michel-Lévy interference colour chart: column i shows a non-dispersive plate at 45° between
// crossed polars with retardation Γ = max·(i + ½)/width, T(λ) = sin²(πΓ/λ) integrated against the
// illuminant and the CIE 1931 observer (Y = 1 for T ≡ 1). Every row is the same colour.
#include <vector>

#include <glm/vec3.hpp>

#include "core/spectrum/illuminant.h"

namespace pmsim {

// Linear sRGB, width*height*3 floats, top row first.
std::vector<float> michel_levy_chart(int width, int height, double max_retardation_nm,
                                     Illuminant illuminant = Illuminant::D65);
// XYZ (Y = 1 reference) of one retardation, crossed polars (or parallel: the complement).
glm::dvec3 michel_levy_xyz(double retardation_nm, Illuminant illuminant, bool parallel_polars = false);

}  // namespace pmsim
