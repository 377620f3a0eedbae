#include "core/microscope/section_reorient.h"

namespace pmsim {

void reorient_section_grains(nlohmann::json& section, std::uint64_t seed) {
  if (!section.contains("grains") || !section["grains"].is_array()) return;  // section_from_json names the fault
  std::uint64_t index = 0;
  for (auto& grain : section["grains"])
    if (grain.is_object()) reorient_section_grain(grain, seed, index++);
}

void reorient_section_grain(nlohmann::json& grain, std::uint64_t seed, std::uint64_t index) {
  const auto e = uniform_euler_deg(seed, index);
  grain["euler_deg"] = {e[0], e[1], e[2]};
  for (const char* legacy : {"optic_axis", "x_axis", "z_axis", "elongation_deg"}) grain.erase(legacy);
}

}  // namespace pmsim
