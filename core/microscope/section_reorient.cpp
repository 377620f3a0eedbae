#include "core/microscope/section_reorient.h"

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

void reorient_section_grains(nlohmann::json& section, std::uint64_t seed) {
  if (!section.contains("grains") || !section["grains"].is_array()) return;  // section_from_json names the fault
  std::uint64_t index = 0;
  for (auto& grain : section["grains"]) {
    if (!grain.is_object()) continue;
    const auto e = uniform_euler_deg(seed, index++);
    grain["euler_deg"] = {e[0], e[1], e[2]};
    for (const char* legacy : {"optic_axis", "x_axis", "z_axis", "elongation_deg"}) grain.erase(legacy);
  }
}

}  // namespace pmsim
