#pragma once
// The grain list of pmsim-render --grains (core/microscope/grain_report.h) as JSON:
//   {"section": name, "stage_deg", "polarizer_deg", "thickness_um", "mm_per_pixel",
//    "index_wavelength_nm": 589.3, "retardation_wavelength_nm": 550,
//    "grains": [{"id", "mineral", "euler_deg": [φ1, Φ, φ2] | null, "area_px",
//                "cleavage_traces_deg": [...], "elongation_deg": x | null,
//                "extinction_stage_deg": [...], "extinction_angle_deg": x | null,
//                "sign_of_elongation": "length-slow" | "length-fast" | null,
//                "retardation_nm", "twin": {"law", "extinction_stage_deg",
//                "cross": {"law", "extinction_stage_deg"} (cross-hatched grains only)} (twinned grains only)}, …]}
// Angles in degrees; image angles counter-clockwise from +x at the current stage angle.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/microscope/grain_report.h"

namespace pmsim {

nlohmann::json grain_report_json(const GrainReport& r);
nlohmann::json grain_reports_json(const Scene& scene, const SectionMap& section,
                                  const std::vector<GrainReport>& grains);
// Atomic (core/io/atomic_file.h); throws std::runtime_error naming the path on failure.
void write_grain_report_file(const std::string& path, const Scene& scene, const SectionMap& section,
                             const std::vector<GrainReport>& grains);

}  // namespace pmsim
