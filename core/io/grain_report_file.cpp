#include "core/io/grain_report_file.h"

#include "core/io/atomic_file.h"
#include "core/microscope/view_geometry.h"
#include "core/render/brightness_test.h"

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
            {"retardation_nm", r.retardation_nm},
            {"opaque", r.opaque},
            // Whether the indicatrix (and so every extinction value above) is the mineral file's
            // published optical orientation or a stand-in on the crystal frame (issue 22).
            {"optics", grain_optics_name(r)}};
  if (r.twin) {
    j["twin"] = {{"law", r.twin->law}, {"extinction_stage_deg", r.twin->extinction_stage_deg}};
    if (!r.twin->cross_law.empty())
      j["twin"]["cross"] = {{"law", r.twin->cross_law}, {"extinction_stage_deg", r.twin->cross_extinction_stage_deg}};
  }
  if (r.alteration) j["alteration"] = {{"mineral", r.alteration->mineral}, {"vein_mm", r.alteration->vein_mm}};
  if (const auto& in = r.inclusions) {
    j["inclusions"] = {{"mineral", in->mineral},
                       {"size_mm", in->size_mm},
                       {"rim_trail_deg", in->rim_trail_deg},
                       {"core_trail_deg", in->core_trail_deg},
                       {"rotation_deg", in->rotation_deg},
                       {"habit", in->habit}};
    if (in->halo_radius_mm > 0.0)
      j["inclusions"]["halo"] = {{"radius_mm", in->halo_radius_mm}, {"darkening", in->halo_darkening}};
  }
  if (const auto& o = r.overgrowth)
    j["overgrowth"] = {{"habit_scale", o->habit_scale},
                       {"detrital_radius_mm", o->detrital_radius_mm},
                       {"dust", o->dust_mineral.empty() ? json(nullptr) : json(o->dust_mineral)}};
  if (const auto& m = r.myrmekite)
    j["myrmekite"] = {{"host", m->host},
                      {"bulbs", m->bulbs},
                      {"quartz", m->quartz_mineral},
                      {"quartz_extinction_stage_deg", m->quartz_extinction_stage_deg}};
  if (r.subgrains)
    j["subgrains"] = {{"width_mm", r.subgrains->width_mm},
                      {"step_deg", r.subgrains->step_deg},
                      {"extinction_sweep_deg", r.subgrains->extinction_sweep_deg ? json(*r.subgrains->extinction_sweep_deg) : json(nullptr)}};
  // The compensator test by brightness (render/brightness_test.h): the luminance at 45° alone,
  // with the accessory adding and subtracting, and which way it reads.
  if (r.retardation_nm > 0.0) {
    json tests = json::object();
    for (const auto& [name, accessory] : {std::pair{"mica", Compensator::Mica}, std::pair{"gypsum", Compensator::Gypsum}}) {
      const BrightnessTest t = brightness_test(r.retardation_nm, accessory);
      tests[name] = {{"y_alone", t.y_alone}, {"y_addition", t.y_addition}, {"y_subtraction", t.y_subtraction},
                     {"reading", t.reading}};
    }
    j["brightness_test"] = std::move(tests);
  }
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
