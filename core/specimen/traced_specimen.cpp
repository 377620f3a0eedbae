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
  // Between the polars the Jones tracer carries the analyzer's vibration (plane_light_options
  // passes analyzer_in and analyzer_deg), but no accessory plate: with a compensator inserted the
  // traced image could not show its colours, so such a scene keeps the flat image.
  if (scene.analyzer_in && scene.compensator != Compensator::None) return false;
  // An EBSD map shown with opaque non-indexed points has a medium the slab tracer cannot absorb
  // in: it keeps the flat image.
  return !load_scene_section(scene)->has_opaque_domain;
}

RenderImage render_traced_specimen(const Scene& scene, const std::function<void(const RenderImage&)>& progress,
                                   const std::atomic<bool>* cancel) {
  if (!is_traced_specimen(scene)) throw std::invalid_argument("render_traced_specimen: not a traced specimen");
  if (scene.sample.type == SampleType::Grains) return render_grain_mount(scene, progress, cancel);
  const std::shared_ptr<const SpecimenScene> slab = section_slab(scene);
  // Traced forward from the condenser's cone, with the analyzer in or out: it converges far
  // faster than backward (forward_plane_light.h).
  std::string report = "thin section slab: " + forward_model_report(scene.analyzer_in);
  // An EBSD map: what it became, as the flat image's report says.
  if (const MapSectionFacts* f = map_section_facts(*load_scene_section(scene)))
    report += "; " + map_section_summary(*f);
  return render_plane_light_forward_as(report, *slab, plane_light_options(scene), progress, cancel);
}

}  // namespace pmsim
