#include "core/specimen/grain_mount_render.h"

#include <algorithm>

#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/microscope/view_geometry.h"

namespace pmsim {

std::unique_ptr<SpecimenScene> grain_mount_specimen(const Scene& scene) {
  ScatterOptions so;
  so.field_width_um = so.field_height_um = 4000.0;
  const std::vector<FragmentShape> fragments = scatter_fragments(so);
  const Crystal mineral =
      scene.sample.crystal ? crystal_from_indices(*scene.sample.crystal) : find_mineral(scene.sample.mineral);
  const ImmersionLiquid liquid = immersion_liquid(scene.sample.medium_index.value_or(kDefaultGrainMountIndex));
  return std::make_unique<SpecimenScene>(fragments, mineral, liquid, find_medium("N-BK7"), find_medium("air"));
}

PlaneLightOptions plane_light_options(const Scene& scene) {
  PlaneLightOptions o;
  o.width = scene.render.width;
  o.height = scene.render.height;
  o.um_per_px = 1000.0 * mm_per_pixel(scene, o.width, o.height);
  o.centre_um = {1000.0 * scene.stage.x_mm, 1000.0 * scene.stage.y_mm};
  o.stage_rad = radians(scene.stage_deg);
  o.focus_um = scene.focus_um;
  o.objective_na = scene.objective.na;
  o.condenser_aperture_na = scene.condenser.aperture_na;
  o.polarizer_rad = radians(scene.polarizer_deg);
  o.analyzer_in = scene.analyzer_in;
  o.analyzer_rad = radians(scene.analyzer_deg);
  o.illuminant = scene.illuminant;
  o.single_wavelength_nm = scene.render.single_wavelength_nm;
  o.spp = scene.render.spp > 0 ? scene.render.spp : 64;
  return o;
}

RenderImage render_grain_mount(const Scene& scene, const std::function<void(const RenderImage&)>& progress,
                               const std::atomic<bool>* cancel) {
  const auto specimen = grain_mount_specimen(scene);
  return render_plane_light(*specimen, plane_light_options(scene), progress, nullptr, cancel);
}

}  // namespace pmsim
