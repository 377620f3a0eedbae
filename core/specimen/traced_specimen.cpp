#include "core/specimen/traced_specimen.h"

#include <stdexcept>

#include "core/microscope/map_section.h"
#include "core/specimen/forward_plane_light.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/section_slab.h"

namespace pmsim {

bool is_traced_specimen(const Scene& scene) {
  if (!scene.sample_in) return false;
  if (scene.sample.type == SampleType::Grains) return true;
  if (scene.sample.type != SampleType::Section || !scene.optics.relief) return false;
  if (scene.mode != ViewMode::Ortho || scene.bertrand_in) return false;
  // An accessory is applied to the traced response (specimen_response.h), so a compensator no
  // longer sends a section to the flat image. An EBSD map shown with opaque non-indexed points
  // has a medium the slab tracer cannot absorb in: it keeps the flat image.
  return !load_scene_section(scene)->has_opaque_domain;
}

namespace {

// What the response's settings are judged at, and what the specimen reports it became.
ResponseRenderOptions traced_response_options(const Scene& scene, ResponseCoverage coverage) {
  ResponseRenderOptions o;
  o.light = plane_light_options(scene);
  o.coverage = coverage;
  o.estimate_at = instrument_settings(scene);
  if (scene.sample.type == SampleType::Grains) {
    o.model_report = "grain mount: " + forward_model_report(scene.analyzer_in);
  } else {
    o.model_report = "thin section slab: " + forward_model_report(scene.analyzer_in);
    // An EBSD map: what it became, as the flat image's report says.
    if (const MapSectionFacts* f = map_section_facts(*load_scene_section(scene)))
      o.model_report += "; " + map_section_summary(*f);
  }
  o.model_report += "; response composed per frame (Mueller blocks, 32 bands)";
  return o;
}

}  // namespace

ResponseProgress render_traced_response(const Scene& scene, ResponseCoverage coverage,
                                        const std::function<void(const ResponseProgress&)>& progress,
                                        const std::atomic<bool>* cancel, const std::function<bool()>& hold) {
  if (!is_traced_specimen(scene)) throw std::invalid_argument("render_traced_response: not a traced specimen");
  const std::shared_ptr<const SpecimenScene> specimen =
      scene.sample.type == SampleType::Grains ? grain_mount_specimen_cached(scene) : section_slab(scene);
  ResponseRenderOptions o = traced_response_options(scene, coverage);
  o.hold = hold;
  return render_specimen_response(*specimen, o, progress, cancel);
}

bool same_specimen_response(const Scene& rendered, const Scene& next) {
  Scene a = rendered, b = next;
  for (Scene* s : {&a, &b}) {
    s->stage_deg = 0.0;
    s->polarizer_deg = 0.0;
    s->analyzer_deg = 0.0;
    s->analyzer_in = true;
    s->compensator = Compensator::None;
    s->compensator_position = 0.0;
    s->render.exposure_ev = 0.0;
    s->render.vision = ColourVision::Normal;
  }
  return a == b;
}

RenderImage render_traced_specimen(const Scene& scene, const std::function<void(const RenderImage&)>& progress,
                                   const std::atomic<bool>* cancel) {
  if (!is_traced_specimen(scene)) throw std::invalid_argument("render_traced_specimen: not a traced specimen");
  const InstrumentSettings instrument = instrument_settings(scene);
  const ResponseProgress last = render_traced_response(
      scene, ResponseCoverage::Field,
      [&](const ResponseProgress& p) {
        if (progress) progress(compose_progress(p, instrument));
      },
      cancel);
  return compose_progress(last, instrument);
}

}  // namespace pmsim
