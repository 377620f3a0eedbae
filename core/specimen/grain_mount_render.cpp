#include "core/specimen/grain_mount_render.h"

#include <algorithm>
#include <string>

#include "core/base/build_cache.h"
#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/microscope/view_geometry.h"
#include "core/specimen/forward_plane_light.h"

namespace pmsim {

std::vector<glm::dvec3> good_cleavage_normals(const std::string& mineral) {
  std::vector<glm::dvec3> out;
  const MineralCrystallography* mc = find_mineral_crystallography(mineral);
  if (!mc) return out;
  const bool isotropic = find_mineral(mineral).symmetry() == CrystalSymmetry::Isotropic;
  // Without an optical orientation the indicatrix axes of an anisotropic mineral are not placed in
  // its lattice: its planes cannot be put in the fragment's (indicatrix) frame.
  if (!isotropic && !mc->orientation) return out;
  for (const Cleavage& c : mc->cleavage) {
    if (c.quality != CleavageQuality::Perfect && c.quality != CleavageQuality::VeryGood &&
        c.quality != CleavageQuality::Good)
      continue;
    // The plane normal in the crystal Cartesian frame, then in the indicatrix frame (X, Y, Z the
    // columns of indicatrix_axes): its components along them.
    const glm::dvec3 n = plane_normal(mc->cell, c.plane);
    out.push_back(isotropic ? n : glm::transpose(mc->indicatrix_axes) * n);
  }
  return out;
}

std::unique_ptr<SpecimenScene> grain_mount_specimen(const Scene& scene) {
  ScatterOptions so;
  so.field_width_um = so.field_height_um = 4000.0;
  if (!scene.sample.crystal) so.cleavage_normals = good_cleavage_normals(scene.sample.mineral);
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
  // render.wavelengths, as every renderer reads it (0: the renderer's own choice); with the
  // analyzer in never fewer than kCrossedPolarBands (interference colours need 12.5 nm bands).
  if (scene.render.wavelengths > 0) o.bands = std::min(scene.render.wavelengths, kMaxTracedBands);
  // Like every image: stop at render.tolerance (split-half estimate), or at render.spp if set.
  // Unset, 256 traces a pixel bound plane light (a render stops long before at the default
  // tolerance: the 256² garnet mount after 2 passes), so that a CLI render ends.
  // Between the polars (traced forward, 3 traces a pixel a pass, 32 bands on a subgrid) the
  // granite section converges to a split-half estimate of ~1 by 64 traces a pixel and to ~0.6
  // only by 256 (its cracks and twin lamellae, bench section-granite-crossed at 256²): 64 bound
  // that CLI render (65 s for the default 512² granite on 2 idle cores, where 256 took 4 min).
  o.spp = scene.render.spp > 0 ? scene.render.spp : scene.analyzer_in ? 64 : 256;
  o.tolerance_de2000 = scene.render.tolerance_de2000;
  o.preview_factor = 4;
  return o;
}

std::shared_ptr<const SpecimenScene> grain_mount_specimen_cached(const Scene& scene) {
  static BuildCache<std::string, SpecimenScene, Keep::Last> cache;
  if (scene.sample.crystal) return grain_mount_specimen(scene);
  const std::string key = scene.sample.mineral + "|" +
                          std::to_string(scene.sample.medium_index.value_or(kDefaultGrainMountIndex));
  return cache.get(key, [&] { return grain_mount_specimen(scene); });
}

}  // namespace pmsim
