#pragma once
// A solid-solution series: principal indices tabulated against composition (mol % of one end
// member), interpolated linearly between the tabulated compositions. Plagioclase (An0–An100) and
// olivine (Fo0–Fo100) are the series whose optics a thin-section course reads off: the optic
// sign of olivine flips near Fo85–90, the 2V of plagioclase swings about 90° (Deer, Howie &
// Zussman 2013; Nesse 2012). 2V is never tabulated as data: it follows from the interpolated
// indices (optic_angle_2v_rad, crystal.h); each point may carry the literature 2Vz it must
// reproduce, which the tests check.
//
// Mineral-file key (optional):
//   "series": {"component": "An", "complement": "Ab", "source": "...",
//              "points": [{"composition": 0, "nalpha": N, "nbeta": N, "ngamma": N,
//                          "optic_angle_2vz_deg": 2Vz}, ...]}
//   compositions strictly increasing from 0 to 100; "complement" (optional) names the other end
//   member, so that "olivine:Fa10" is read as Fo90.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace pmsim {

class JsonReader;

struct SeriesPoint {
  double composition = 0;                     // mol % of the component
  glm::dvec3 indices{1.5};                    // nα, nβ, nγ at 589 nm
  std::optional<double> literature_2vz_deg;   // the published 2Vz at this composition (checked)
};

struct MineralSeries {
  std::string component;   // "An", "Fo": the end member whose mol % the composition gives
  std::string complement;  // "Ab", "Fa" (may be empty)
  std::vector<SeriesPoint> points;
  std::string source;
  // Linear interpolation of each index between the bracketing points; composition in [0, 100].
  glm::dvec3 indices_at(double composition) const;
};

// Reads and checks the "series" object (biaxial nα ≤ nβ ≤ nγ at every point, compositions
// 0 … 100 strictly increasing). Throws InputError naming file, key and value.
MineralSeries read_mineral_series(const JsonReader& series);

// The series of a mineral name (any form find_mineral takes); nullptr when it is none. Throws
// InputError for an unknown mineral.
const MineralSeries* find_mineral_series(std::string_view name);

// A name without its composition: "plagioclase:An32" → "plagioclase"; "quartz" stays. A student
// names the series, not the section's composition.
std::string series_name(std::string_view name);

}  // namespace pmsim
