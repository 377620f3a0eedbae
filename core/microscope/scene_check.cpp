#include "core/microscope/scene_check.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/crystal/crystal_cut.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/ebsd/read_orientation_map.h"
#include "core/microscope/sample_source.h"
#include "core/texture/rock_recipe.h"

namespace pmsim {

namespace {
void require(bool ok, const std::string& file, const char* key, const std::string& value,
             const std::string& why) {
  if (!ok) throw InputError(file, key, value, why);
}
// Numbers in messages as the readers show them (core/base/json_reader.h).
std::string num(double v) { return number_text(v); }
// Two decimals, as indices are written (1.40, not 1.4).
std::string fixed2(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", v);
  return b;
}
// "[x,y,z]" (appending, not "[" + …: GCC 12 warns falsely on that pattern, PR 105651).
std::string vec_text(const std::array<double, 3>& v) {
  std::string t = "[";
  t += num(v[0]);
  t += ',';
  t += num(v[1]);
  t += ',';
  t += num(v[2]);
  t += ']';
  return t;
}
// sample.cut needs a library mineral with crystallographic data, and north in the plane; the
// syntax of both texts was checked when the key was read.
void check_cut(const Scene& s, const std::string& file) {
  const SampleCut& cut = *s.sample.cut;
  std::string shown_cut = "{\"plane\":\"";  // appended: see vec_text
  shown_cut += cut.plane;
  shown_cut += "\",\"north\":\"";
  shown_cut += cut.north;
  shown_cut += "\"}";
  require(!s.sample.crystal, file, "sample.cut", shown_cut,
          "a cut needs a library mineral's lattice; sample.crystal gives indices only");
  if (!mineral_known(s.sample.mineral)) return;  // reported on sample.mineral
  const MineralCrystallography* m = find_mineral_crystallography(s.sample.mineral);
  require(m && m->orientation, file, "sample.cut", shown_cut,
          "mineral '" + s.sample.mineral + "' has no unit cell and optical orientation data");
  const MillerIndices plane = parse_miller_plane(cut.plane);
  const LatticeDirection north = parse_lattice_direction(cut.north);
  const double off_deg = direction_plane_angle_deg(m->cell, plane, north);
  try {
    crystal_to_lab_of_cut(m->cell, plane, north);
  } catch (const BadValue&) {
    throw InputError(file, "sample.cut.north", cut.north,
                     "makes " + num(off_deg) + "° with the plane " + cut.plane + " of " + s.sample.mineral +
                         "; north must lie in the section plane (to 1e-6)");
  }
}

}  // namespace

void check_pixel_count(const Scene& s, const std::string& file, const char* key) {
  const long long n = static_cast<long long>(s.render.width) * s.render.height;
  const bool w = std::string(key) == "render.width";
  require(n <= kMaxRenderPixels, file, key, num(w ? s.render.width : s.render.height),
          "render.width × render.height = " + num(s.render.width) + " × " + num(s.render.height) + " = " +
              std::to_string(n) + " pixels, more than the limit of " + std::to_string(kMaxRenderPixels) +
              " (8192²)");
}

void check_scene(const Scene& s, const std::string& file) {
  auto finite = [&](double v, const char* key) {
    require(std::isfinite(v), file, key, num(v), "not a finite number");
  };
  finite(s.polarizer_deg, "polarizer_deg");
  finite(s.analyzer_deg, "analyzer_deg");
  finite(s.stage_deg, "stage_deg");
  finite(s.objective.magnification, "objective.magnification");
  require(s.objective.magnification > 0 && s.objective.magnification <= kMaxMagnification, file,
          "objective.magnification", num(s.objective.magnification),
          std::string("must be in (0, ") + num(kMaxMagnification) + "]");
  finite(s.eyepiece.field_number_mm, "eyepiece.field_number_mm");
  require(s.eyepiece.field_number_mm > 0 && s.eyepiece.field_number_mm <= kMaxFieldNumberMm, file,
          "eyepiece.field_number_mm", num(s.eyepiece.field_number_mm),
          std::string("must be in (0, ") + num(kMaxFieldNumberMm) + "] mm");
  finite(s.stage.x_mm, "stage.x_mm");
  finite(s.stage.y_mm, "stage.y_mm");
  const std::string travel =
      std::string("must be in [-") + num(kMaxStageTravelMm) + ", " + num(kMaxStageTravelMm) + "] mm";
  require(std::abs(s.stage.x_mm) <= kMaxStageTravelMm, file, "stage.x_mm", num(s.stage.x_mm), travel);
  require(std::abs(s.stage.y_mm) <= kMaxStageTravelMm, file, "stage.y_mm", num(s.stage.y_mm), travel);
  // A dry objective and condenser collect at most sin θ < 1 in air.
  require(s.objective.na > 0 && s.objective.na < 1, file, "objective.na", num(s.objective.na),
          "numerical aperture in air must be in (0, 1)");
  require(s.condenser.na > 0 && s.condenser.na < 1, file, "condenser.na", num(s.condenser.na),
          "numerical aperture in air must be in (0, 1)");
  // The aperture diaphragm cannot open beyond the condenser's own NA.
  require(std::isfinite(s.condenser.aperture_na) && s.condenser.aperture_na >= 0 &&
              s.condenser.aperture_na <= s.condenser.na,
          file, "condenser.aperture_na", num(s.condenser.aperture_na),
          "must be in [0, condenser.na = " + num(s.condenser.na) + "]");
  require(std::isfinite(s.focus_um) && std::abs(s.focus_um) <= kMaxFocusUm, file, "focus_um", num(s.focus_um),
          std::string("must be in [-") + num(kMaxFocusUm) + ", " + num(kMaxFocusUm) + "] µm");
  if (s.sample.medium_index)
    require(std::isfinite(*s.sample.medium_index) && *s.sample.medium_index >= kMinMediumIndex &&
                *s.sample.medium_index <= kMaxMediumIndex,
            file, "sample.medium_index", num(*s.sample.medium_index), "n_D must be in [" + fixed2(kMinMediumIndex) + ", " + fixed2(kMaxMediumIndex) + "]");
  require(std::isfinite(s.sample.thickness_um) && s.sample.thickness_um > 0 && s.sample.thickness_um <= kMaxThicknessUm,
          file, "sample.thickness_um", num(s.sample.thickness_um), std::string("must be in (0, ") + num(kMaxThicknessUm) + "] µm");
  for (auto [v, key] :
       {std::pair{&s.sample.optic_axis, "sample.optic_axis"}, std::pair{&s.sample.x_axis, "sample.x_axis"},
        std::pair{&s.sample.z_axis, "sample.z_axis"}}) {
    const auto& a = *v;
    const double len2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    require(std::isfinite(len2) && len2 > 1e-24, file, key, vec_text(a),
            "a direction cannot be the zero vector");
  }
  {
    // The biaxial frame: x_axis (nα) ⟂ z_axis (nγ). Parallel ones define no orientation; oblique
    // ones are a typo (the renderer would silently replace x_axis by its part ⟂ z_axis). The
    // tolerance, |x̂·ẑ| ≤ 1e-6, accepts axes written to six or more significant digits.
    const auto& x = s.sample.x_axis;
    const auto& z = s.sample.z_axis;
    const double cx = x[1] * z[2] - x[2] * z[1], cy = x[2] * z[0] - x[0] * z[2],
                 cz = x[0] * z[1] - x[1] * z[0];
    const double lx = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    const double lz = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
    require(std::sqrt(cx * cx + cy * cy + cz * cz) > 1e-9 * lx * lz, file, "sample.x_axis", vec_text(x),
            "must not be parallel to sample.z_axis");
    const double cos_xz = (x[0] * z[0] + x[1] * z[1] + x[2] * z[2]) / (lx * lz);
    require(std::abs(cos_xz) <= 1e-6, file, "sample.x_axis", vec_text(x),
            "must be perpendicular to sample.z_axis " + vec_text(z) + " (to 1e-6)");
  }
  if (s.sample.crystal) {
    try {
      check_crystal_indices(*s.sample.crystal);
    } catch (const BadValue& b) {
      const CrystalIndices& c = *s.sample.crystal;
      throw InputError(file, "sample.crystal",
                       c.uniaxial ? num(c.no) + ", " + num(c.ne)
                                  : num(c.nalpha) + ", " + num(c.nbeta) + ", " + num(c.ngamma),
                       b.why);
    }
  } else {
    // Whatever the sample type: a typo on a section scene must not wait until the user switches
    // to a plate to be reported on a key they did not touch.
    if (const auto problem = mineral_name_problem(s.sample.mineral))
      throw InputError(file, "sample.mineral", s.sample.mineral, *problem);
  }
  if (s.sample.cut) check_cut(s, file);
  if (s.sample_in && s.sample.type == SampleType::Section)
    require(section_known(s.sample.section), file, "sample.section", s.sample.section,
            "no such thin-section file in assets/sections or rock in assets/rocks");
  if (s.sample.seed) {
    require(*s.sample.seed >= 0, file, "sample.seed", num(*s.sample.seed), "must be in [0, 2147483647]");
    require(rock_recipe_path(s.sample.section) != "", file, "sample.seed", num(*s.sample.seed),
            "grows rocks from their recipe (assets/rocks); '" + s.sample.section +
                "' is not one (sample.orientation_seed gives a section file new orientations)");
  }
  if (s.sample.orientation_seed) {
    require(*s.sample.orientation_seed >= 0, file, "sample.orientation_seed", num(*s.sample.orientation_seed),
            "must be in [0, 2147483647]");
    // A map's orientations are measurements: redrawing them would no longer be that rock.
    require(!is_orientation_map_path(s.sample.section), file, "sample.orientation_seed",
            num(*s.sample.orientation_seed), "applies to thin-section files, not to an EBSD map");
  }
  require(medium_known(s.sample.medium), file, "sample.medium", s.sample.medium, "unknown mounting medium");
  require(std::isfinite(s.compensator_position) && s.compensator_position >= 0 && s.compensator_position <= 1,
          file, "compensator_position", num(s.compensator_position), "must be in [0, 1]");
  const std::string side = std::string("must be in 1…") + num(kMaxRenderSide);
  require(s.render.width > 0 && s.render.width <= kMaxRenderSide, file, "render.width", num(s.render.width), side);
  require(s.render.height > 0 && s.render.height <= kMaxRenderSide, file, "render.height", num(s.render.height), side);
  check_pixel_count(s, file, "render.height");
  require(s.render.spp >= 0 && s.render.spp <= kMaxSpp, file, "render.spp", num(s.render.spp),
          "must be ≥ 0 (0: until converged)");
  require(s.render.wavelengths >= 0 && s.render.wavelengths <= kMaxWavelengths, file, "render.wavelengths",
          num(s.render.wavelengths), std::string("must be in 0…") + num(kMaxWavelengths) + " (0: until converged)");
  require(s.render.single_wavelength_nm == 0 ||
              (s.render.single_wavelength_nm >= kMinSingleWavelengthNm &&
               s.render.single_wavelength_nm <= kMaxSingleWavelengthNm),
          file, "render.single_wavelength_nm", num(s.render.single_wavelength_nm),
          std::string("must be 0 (white light) or within ") + num(kMinSingleWavelengthNm) + "–" +
              num(kMaxSingleWavelengthNm) + " nm");
  require(std::isfinite(s.render.tolerance_de2000) && s.render.tolerance_de2000 > 0, file, "render.tolerance",
          num(s.render.tolerance_de2000), "must be > 0 (CIEDE2000)");
  require(std::isfinite(s.render.exposure_ev) && s.render.exposure_ev >= kMinExposureEv &&
              s.render.exposure_ev <= kMaxExposureEv,
          file, "render.exposure_ev", num(s.render.exposure_ev), std::string("must be in −") + num(-kMinExposureEv) + "…" + num(kMaxExposureEv) + " (stops)");
  require(s.optics.lens_depth >= 0 && s.optics.lens_depth <= kMaxLensDepth, file, "optics.lens_depth",
          num(s.optics.lens_depth), std::string("must be in 0…") + num(kMaxLensDepth));
}

}  // namespace pmsim
