#include "core/crystal/uniform_orientation.h"

#include <cmath>
#include <numbers>

#include "core/base/splitmix64.h"

namespace pmsim {

std::array<double, 3> uniform_euler_deg(std::uint64_t seed, std::uint64_t grain) {
  std::uint64_t state = splitmix64(seed ^ splitmix64(grain + 0x7F4A7C15ull));
  double u[3];
  for (double& x : u) {
    state = splitmix64(state);
    x = unit_interval(state);
  }
  const double phi_deg = std::acos(1.0 - 2.0 * u[1]) * 180.0 / std::numbers::pi;
  return {360.0 * u[0], phi_deg, 360.0 * u[2]};
}

}  // namespace pmsim
