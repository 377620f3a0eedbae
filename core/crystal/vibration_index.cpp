#include "core/crystal/vibration_index.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace pmsim {

double vibration_index(const Crystal& crystal, const glm::dmat3& R, double wavelength_nm,
                       const glm::dvec3& vibration) {
  const glm::dvec3 n = crystal.principal_indices(wavelength_nm);
  if (crystal.symmetry() == CrystalSymmetry::Isotropic) return n.x;
  const glm::dvec3 v = glm::normalize(vibration);
  const double a = glm::dot(v, R[0]), b = glm::dot(v, R[1]), c = glm::dot(v, R[2]);
  return 1.0 / std::sqrt(a * a / (n.x * n.x) + b * b / (n.y * n.y) + c * c / (n.z * n.z));
}

}  // namespace pmsim
