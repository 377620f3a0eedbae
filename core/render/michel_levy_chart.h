#pragma once
// The Michel-Lévy interference colour chart: column i shows a non-dispersive plate at 45° between
// crossed polars with retardation Γ = max·(i + ½)/width, T(λ) = sin²(πΓ/λ) integrated against the
// illuminant and the CIE 1931 observer (Y = 1 for T ≡ 1). Every row is the same colour.
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/spectrum/illuminant.h"

namespace pmsim {

// Linear sRGB, width*height*3 floats, top row first.
std::vector<float> michel_levy_chart(int width, int height, double max_retardation_nm,
                                     Illuminant illuminant = Illuminant::D65);
// XYZ (Y = 1 reference) of one retardation, crossed polars (or parallel: the complement).
glm::dvec3 michel_levy_xyz(double retardation_nm, Illuminant illuminant, bool parallel_polars = false);

// The chart's birefringence lines: thickness d on the vertical axis (0 at the bottom, up to
// max_thickness_um at the top), retardation Γ on the horizontal axis; a mineral of birefringence
// Δn lies on the straight line Γ = d·Δn through the origin (Γ in nm = 1000·d[µm]·Δn).
struct MichelLevyLine {
  double birefringence = 0.0;  // Δn
  std::string label;           // e.g. "0.009"
  // End points in chart units: x = Γ in nm, y = thickness in µm. `from` is the origin; `to` is
  // where the line leaves the chart (top edge, or right edge for large Δn).
  glm::dvec2 from{0.0}, to{0.0};
  bool ends_on_top = true;  // label goes above the top edge (else beyond the right edge)
  // The same end points as fractions of the chart image: x 0…1 from the left, y 0…1 from the top.
  glm::dvec2 from_frac{0.0}, to_frac{0.0};
};

// The standard set of labelled lines: 0.001 … 0.2 (the range of common rock-forming minerals, from
// apatite/chlorite to calcite), as printed on the usual charts.
const std::vector<double>& michel_levy_standard_birefringences();
// Lines for the given birefringences (Δn ≤ 0 skipped) over a chart spanning 0…max_retardation_nm
// and 0…max_thickness_um.
std::vector<MichelLevyLine> michel_levy_lines(
    double max_retardation_nm, double max_thickness_um = 50.0,
    const std::vector<double>& birefringences = michel_levy_standard_birefringences());
// The chart with its birefringence lines drawn (dark, 1 px, antialiased) over the colours; rows
// now differ (thickness runs from 0 at the bottom row to max_thickness_um at the top).
std::vector<float> michel_levy_chart_with_lines(
    int width, int height, double max_retardation_nm, double max_thickness_um = 50.0,
    Illuminant illuminant = Illuminant::D65,
    const std::vector<double>& birefringences = michel_levy_standard_birefringences());

}  // namespace pmsim
