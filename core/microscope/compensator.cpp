#include "core/microscope/compensator.h"

#include <algorithm>
#include <cmath>

#include "core/base/conventions.h"

namespace pmsim {

namespace {
// Columns: crystal X, Y, Z in the lab.
glm::dmat3 axes(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z) { return glm::dmat3(x, y, z); }
}  // namespace

CompensatorPlate make_compensator(Compensator kind, double position) {
  CompensatorPlate c;
  if (kind == Compensator::None) return c;
  double gamma_550 = 0.0;
  double birefringence_550 = 0.0;
  if (kind == Compensator::Gypsum) {
    // (010) plate: Y = nβ along the axis, Z = nγ (slow) NE–SW, X = nα NW–SE.
    c.spec.crystal = &find_mineral("gypsum");
    c.spec.crystal_to_lab = axes(kSlotFast, kLightDirection, kSlotSlow);
    const glm::dvec3 n = c.spec.crystal->principal_indices(550.0);
    birefringence_550 = n.z - n.x;
    gamma_550 = 550.0;
  } else if (kind == Compensator::Mica) {
    // (001) cleavage: X = nα ≈ along the axis, Y = nβ NW–SE, Z = nγ (slow) NE–SW.
    c.spec.crystal = &find_mineral("muscovite");
    c.spec.crystal_to_lab = axes(kLightDirection, kSlotFast, kSlotSlow);
    const glm::dvec3 n = c.spec.crystal->principal_indices(550.0);
    birefringence_550 = n.z - n.y;
    gamma_550 = 147.0;
  } else {
    // Quartz (optically positive: ne > no, so the c axis is the slow direction), c along NE–SW.
    c.spec.crystal = &find_mineral("quartz");
    c.spec.crystal_to_lab = axes(kSlotFast, kLightDirection, kSlotSlow);
    const glm::dvec3 n = c.spec.crystal->principal_indices(550.0);
    birefringence_550 = n.z - n.x;
    gamma_550 = 4.0 * 550.0 * std::clamp(position, 0.0, 1.0);
  }
  c.design_retardation_nm = gamma_550;
  if (gamma_550 <= 0.0 || birefringence_550 <= 0.0) return c;  // wedge fully out: nothing in the path
  c.present = true;
  c.spec.thickness_um = gamma_550 / birefringence_550 * 1e-3;
  c.spec.fresnel = false;
  c.spec.n_outside = 1.54;
  return c;
}

double compensator_retardation_nm(const CompensatorPlate& c, double wavelength_nm) {
  if (!c.present) return 0.0;
  return plate_modes(c.spec, kLightDirection, wavelength_nm).retardation_nm;
}

}  // namespace pmsim
