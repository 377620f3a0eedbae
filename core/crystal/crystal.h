#pragma once
// An optically anisotropic crystal: its indicatrix (three principal refractive indices with
// dispersion), pleochroic absorption along the principal vibration directions, and optical
// activity (quartz). The orientation of the indicatrix in the lab frame is not part of the crystal:
// callers pass it to the plate model (core/crystal/plate.h) as a matrix whose columns are the
// crystal X, Y, Z axes.
//
// Principal axes: biaxial crystals use X = nα, Y = nβ, Z = nγ (nα ≤ nβ ≤ nγ, the optical-
// mineralogy convention of Nesse 2012 §7); uniaxial ones use X = Y = nω (no), Z = nε (ne), Z being
// the optic axis c; isotropic ones have all three equal.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/crystal_indices.h"

namespace pmsim {

enum class CrystalSymmetry { Isotropic, Uniaxial, Biaxial };

// Dispersion of one principal index; a plain tagged value (no virtual call per evaluation).
struct IndexDispersion {
  enum class Model {
    Constant,  // n = A
    Ghosh1999,  // n² = A + B/(1 − C/λ²) + D/(1 − E/λ²), λ in µm (Ghosh, Opt. Commun. 163, 95 (1999))
    Cauchy      // n = A + B/λ² + C/λ⁴, λ in µm
  };
  Model model = Model::Constant;
  double A = 1.0, B = 0.0, C = 0.0, D = 0.0, E = 0.0;
  double n(double wavelength_nm) const;
};

// Tabulated intensity attenuation μ(λ) per µm, linearly interpolated, clamped at the ends.
struct AbsorptionTable {
  std::vector<double> wavelength_nm;
  std::vector<double> mu_per_um;
  double mu(double lambda_nm) const;
  bool empty() const { return wavelength_nm.empty(); }
};

// Rotatory power ρ(λ) = A/(λ² − λ0²) (Drude's one-term law of rotatory dispersion; Lowry,
// "Optical Rotatory Power", 1935),
// in rad per µm, λ in µm. Positive = dextrorotatory (clockwise as seen by the observer looking
// toward the source), the convention of chemistry and of "right-handed quartz".
struct RotatoryDispersion {
  double A_rad_um = 0.0;  // rad·µm (ρ·(λ²−λ0²))
  double lambda0_um = 0.0;
  double rho(double wavelength_nm) const;
};

class Crystal {
 public:
  Crystal() = default;

  const std::string& name() const { return name_; }
  CrystalSymmetry symmetry() const { return symmetry_; }
  bool is_constant() const { return constant_; }

  // (n_X, n_Y, n_Z) at λ in vacuum. Constant crystals take the inline fast path.
  glm::dvec3 principal_indices(double wavelength_nm) const {
    return constant_ ? constant_indices_ : dispersive_indices(wavelength_nm);
  }
  // Intensity attenuation μ (per µm, I = I0·e^(−μ·path)) for light vibrating along X, Y, Z
  // (pleochroism); zero for a non-absorbing crystal.
  glm::dvec3 principal_absorption_per_um(double wavelength_nm) const;
  bool absorbing() const { return absorbing_; }
  // Optical activity for light travelling along the optic axis, rad per µm, signed as in
  // RotatoryDispersion (quartz: ≈ 21.7°/mm = 3.79e-4 rad/µm at 589 nm); 0 if none.
  double rotatory_power_rad_per_um(double wavelength_nm) const {
    return optically_active_ ? rotatory_.rho(wavelength_nm) : 0.0;
  }
  bool optically_active() const { return optically_active_; }
  std::string source() const { return source_; }  // citation of the data

  static Crystal uniaxial_constant(std::string name, double no, double ne);
  static Crystal biaxial_constant(std::string name, double nalpha, double nbeta, double ngamma);
  static Crystal isotropic_constant(std::string name, double n);
  // General constructor used by the mineral loader; axes follow the convention above.
  static Crystal make(std::string name, CrystalSymmetry symmetry, IndexDispersion x, IndexDispersion y,
                      IndexDispersion z, std::string source);
  void set_absorption(AbsorptionTable x, AbsorptionTable y, AbsorptionTable z);
  void set_rotatory_power(RotatoryDispersion rho);
  // The same crystal with every absorption coefficient μ times `factor` (its optical density, so
  // its transmittance raised to that power): radiation damage darkening a host round a radioactive
  // inclusion (a pleochroic halo), named `name`.
  Crystal with_absorption_scaled(double factor, std::string name) const;

 private:
  glm::dvec3 dispersive_indices(double wavelength_nm) const;

  std::string name_;
  CrystalSymmetry symmetry_ = CrystalSymmetry::Isotropic;
  bool constant_ = true;
  glm::dvec3 constant_indices_{1.5};
  IndexDispersion disp_[3];
  bool absorbing_ = false;
  AbsorptionTable absorption_[3];
  bool optically_active_ = false;
  RotatoryDispersion rotatory_;
  std::string source_;
};

// The mineral library (assets/minerals/*.json, or $PMSIM_ASSETS/minerals), loaded once.
// A mineral name is, case-insensitively and wherever one is written (scene files, --set,
// section grains): a file's name ("enstatite"), an alias from assets/minerals/aliases.json
// ("opx", "garnet"), or a composition of a solid-solution series, "plagioclase:An35",
// "olivine:Fo88" (integer or decimal mol %, 0..100; "olivine:Fa12" means Fo88). The plain series
// name ("plagioclase") keeps the file's own indices, its default composition.
// canonical_mineral_name: the one spelling of a name, "enstatite" or "plagioclase:An35" (the
// component as the file spells it, the shortest decimal); InputError (value = the name, no key:
// the caller knows it) for an unknown mineral, listing the known ones, or a bad composition.
std::string canonical_mineral_name(std::string_view name);
// The crystal of a name as above; name() is the canonical name. The reference stays valid for
// the process (composition crystals are made once and kept). Throws as canonical_mineral_name.
const Crystal& find_mineral(std::string_view name);
// (alias, target) pairs, sorted by alias, lower case; targets are canonical names.
std::vector<std::pair<std::string, std::string>> mineral_aliases();
// Parses one mineral file; throws InputError naming the file, key and value on bad input.
Crystal load_mineral_file(const std::string& path);
std::vector<std::string> mineral_names();  // sorted, lower case
// Every name a mineral may be given, for error messages: "actinolite, …, zoisite; aliases:
// cpx = augite, …" (file names, then each alias with the canonical name it stands for).
std::string known_minerals_text();
// Constant indices → a constant crystal; applies the index rule of crystal_indices.h, throwing
// InputError with key "no", "nalpha", … (or "" for the order): the caller prefixes its key path.
Crystal crystal_from_indices(const CrystalIndices& c);

// Orientation helpers: the columns of the result are the crystal X, Y, Z axes in the lab frame at
// stage 0°. Both throw std::invalid_argument on a zero (or non-finite) vector.
glm::dmat3 uniaxial_orientation(glm::dvec3 optic_axis);                // Z = optic axis
glm::dmat3 biaxial_orientation(glm::dvec3 x_axis, glm::dvec3 z_axis);  // Gram–Schmidt, z first
// Rotation of the stage by stage_rad counter-clockwise (seen by the observer) about lab z,
// applied to an orientation: R_z(stage)·orientation.
glm::dmat3 rotate_stage(const glm::dmat3& crystal_to_lab, double stage_rad);

// The optic angle 2V measured about Z (the nγ axis), i.e. 2Vz in [0, π]:
// cos²Vz = nα²(nγ² − nβ²) / (nβ²(nγ² − nα²))   (Born & Wolf §15.3; Nesse 2012 ch. 7).
// 2Vz < π/2: Z is the acute bisectrix (optically positive); 2Vz > π/2: X is (negative),
// 2Vx = π − 2Vz. The optic axes lie in the XZ plane at ±Vz from Z. Uniaxial limits: nβ = nα → 0,
// nβ = nγ → π; isotropic (nα = nγ) → 0.
double optic_angle_2v_rad(double nalpha, double nbeta, double ngamma);

}  // namespace pmsim
