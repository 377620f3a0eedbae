#pragma once
// The refractive index a crystal offers to light vibrating along one direction: the radius of its
// indicatrix along that direction, 1/n'² = Σ (v·axis_i)²/n_i² (Nesse 2012 §7, the indicatrix).
// What the specimen tracer's media answer (SpecimenScene::index) and what the Becke-line probes
// report, so that both read the same number from the same crystal and orientation.
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/crystal.h"

namespace pmsim {

// `crystal_to_lab`: the indicatrix axes X, Y, Z as columns in the frame of `vibration` (any
// non-zero vector; normalised here). An isotropic crystal returns its n at every direction.
double vibration_index(const Crystal& crystal, const glm::dmat3& crystal_to_lab, double wavelength_nm,
                       const glm::dvec3& vibration);

}  // namespace pmsim
