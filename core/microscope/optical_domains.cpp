#include "core/microscope/optical_domains.h"

#include <array>

#include "core/base/units.h"
#include "core/crystal/crystal_cut.h"
#include "core/microscope/map_section.h"

namespace pmsim {

namespace {

glm::dvec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

glm::dmat3 sample_orientation(const Crystal& c, const SampleSettings& s) {
  if (s.cut) return cut_plate_orientation(c, s.cut->plane, s.cut->north);  // checked by check_scene
  if (c.symmetry() == CrystalSymmetry::Biaxial) return biaxial_orientation(vec(s.x_axis), vec(s.z_axis));
  return uniaxial_orientation(vec(s.optic_axis));
}

}  // namespace

OpticalDomains optical_domains(const Scene& scene) {
  OpticalDomains out;
  const double stage_rad = radians(scene.stage_deg);
  if (!scene.sample_in) {
    out.domains.push_back({nullptr, glm::dmat3(1.0), scene.sample.thickness_um, "empty stage"});
  } else if (scene.sample.type == SampleType::Section) {
    out.section = load_scene_section(scene);
    // Slide and mounting medium (domains 0, 1) carry no crystal: isotropic, dark between
    // crossed polars.
    for (int d = 0; d < out.section->domain_count(); ++d)
      out.domains.push_back({out.section->crystal_of_domain(d),
                             rotate_stage(out.section->orientation_of_domain(d), stage_rad),
                             scene.sample.thickness_um, out.section->mineral_of_domain(d),
                             out.section->is_opaque(d)});
  } else {
    const Crystal* c;
    if (scene.sample.crystal) {
      out.custom_crystal = std::make_shared<Crystal>(crystal_from_indices(*scene.sample.crystal));
      c = out.custom_crystal.get();
    } else {
      c = &find_mineral(scene.sample.mineral);
    }
    out.domains.push_back({c, rotate_stage(sample_orientation(*c, scene.sample), stage_rad),
                           scene.sample.thickness_um, scene.sample.crystal ? "custom crystal" : c->name()});
  }
  return out;
}

}  // namespace pmsim
