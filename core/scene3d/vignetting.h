#pragma once
// Forward-tracing vignetting estimate of an objective (paper §7: "by forward tracing one can
// calculate the degree and zone of vignetting of the objective"). Rays leave a field point in the
// object plane into the cone of the objective's numerical aperture, uniformly in solid angle,
// and go through the lenses in order with the SML; a ray is vignetted when it misses a lens,
// meets a ledge, or is totally reflected before leaving the last lens.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/lens/lens.h"

namespace pmsim {

struct Objective {
  std::string name;
  std::vector<LensSpec> lenses;  // in the order the light meets them, axis along +z
  double object_z_mm = 0.0;      // object plane z (the axis is the z axis through x = y = 0)
  double na = 0.25;              // object-side numerical aperture in air (sin of the half-angle)
  double field_max_mm = 1.0;     // largest field height to evaluate
  double wavelength_nm = 587.5618;
};
// Keys: type "objective", source, name, lenses (LensSpec objects), object_z_mm, na,
// field_max_mm, wavelength_nm. InputError names file/key/value.
Objective objective_from_json(const nlohmann::json& j, const std::string& file);

struct VignettingPoint {
  double field_mm = 0.0;
  double passed = 0.0;       // fraction of the rays of the NA cone that leave the last lens
  double transmitted = 0.0;  // fraction of the power (natural light) carried by those rays
};
// grid × grid stratified directions per field point (those inside the cone are kept).
std::vector<VignettingPoint> vignetting(const Objective& obj, int field_steps, int grid);
// Pass (1) / vignetted (0) map over the cone, grid × grid over the unit disk of sinθ (cell
// outside the disk: −1), for one field height: the zone of vignetting.
std::vector<int> vignetting_map(const Objective& obj, double field_mm, int grid);

}  // namespace pmsim
