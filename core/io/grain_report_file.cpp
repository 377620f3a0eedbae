#include "core/io/grain_report_file.h"

#include "core/io/atomic_file.h"
#include "core/microscope/view_geometry.h"

namespace pmsim {

using nlohmann::json;

json grain_report_json(const GrainReport& r) {
  json j = {{"id", r.id},
            {"mineral", r.mineral},
            {"euler_deg", r.euler_deg ? json(*r.euler_deg) : json(nullptr)},
            {"area_px", r.area_px},
            {"cleavage_traces_deg", r.cleavage_traces_deg},
            {"elongation_deg", r.elongation_deg ? json(*r.elongation_deg) : json(nullptr)},
            {"extinction_stage_deg", r.extinction_stage_deg},
            {"extinction_angle_deg", r.extinction_angle_deg ? json(*r.extinction_angle_deg) : json(nullptr)},
            {"sign_of_elongation",
             r.sign_of_elongation ? json(sign_of_elongation_name(*r.sign_of_elongation)) : json(nullptr)},
            {"retardation_nm", r.retardation_nm}};
  if (r.twin) j["twin"] = {{"law", r.twin->law}, {"extinction_stage_deg", r.twin->extinction_stage_deg}};
  return j;
}

json grain_reports_json(const Scene& scene, const SectionMap& section,
                        const std::vector<GrainReport>& grains) {
  json list = json::array();
  for (const GrainReport& r : grains) list.push_back(grain_report_json(r));
  return {{"section", section.name},
          {"stage_deg", scene.stage_deg},
          {"polarizer_deg", scene.polarizer_deg},
          {"thickness_um", scene.sample.thickness_um},
          {"mm_per_pixel", mm_per_pixel(scene, scene.render.width, scene.render.height)},
          {"index_wavelength_nm", kGrainReportIndexWavelengthNm},
          {"retardation_wavelength_nm", kGrainReportRetardationWavelengthNm},
          {"grains", std::move(list)}};
}

void write_grain_report_file(const std::string& path, const Scene& scene, const SectionMap& section,
                             const std::vector<GrainReport>& grains) {
  write_text_atomically(path, grain_reports_json(scene, section, grains).dump(2) + "\n");
}

}  // namespace pmsim
