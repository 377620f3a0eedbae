#include "core/crystal/opacity.h"

#include <cmath>

namespace pmsim {

bool is_opaque(const Crystal& c, double thickness_um) {
  if (!c.absorbing()) return false;
  // Every 5 nm: μ is linear between a table's wavelengths (AbsorptionTable::mu), so its least
  // value lies on one of them or at an end; the files tabulate at multiples of 5 nm.
  const double mu_min_needed = -std::log(kOpaqueTransmittance) / thickness_um;
  for (double l = 380.0; l <= 780.0; l += 5.0) {
    const glm::dvec3 mu = c.principal_absorption_per_um(l);
    if (mu.x < mu_min_needed || mu.y < mu_min_needed || mu.z < mu_min_needed) return false;
  }
  return true;
}

}  // namespace pmsim
