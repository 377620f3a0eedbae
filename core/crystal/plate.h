#pragma once
// A plane-parallel anisotropic plate (faces ⟂ lab z) between two half-spaces of one isotropic
// medium: the two plane-wave eigenmodes for a given incident direction and wavelength, and the
// plate's Jones matrix. Model (Debelov & Kozlov 2013 ref. [1]; Born & Wolf §15.2–15.3; Yariv & Yeh
// "Optical Waves in Crystals" ch. 4): the tangential wave vector is conserved at the faces; each
// eigenmode's normal component k_z follows from the Fresnel equation of wave normals (closed form
// for uniaxial crystals, a converged fixed point for biaxial ones); the face amplitudes are exact
// single-interface solutions of the tangential E/H boundary conditions (multiple reflections inside
// the plate are neglected); absorption and optical activity are perturbations of the linear,
// lossless modes. Details and approximations: plate.cpp.
//
// Phase convention (docs/conventions.md): e^{i(k·r − ωt)}, a path adds phase +k0·n·L.
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/crystal.h"
#include "core/optics/jones.h"

namespace pmsim {

// Transverse basis for a direction k (unit, k.z > 0): a = unit(x̂ − (x̂·k)k), b = k × a.
// At k = ẑ: (x̂, ŷ). (a, b, k) is right-handed, so a rotation from a toward b is counter-clockwise
// as the observer sees it.
void transverse_basis(const glm::dvec3& k, glm::dvec3& a, glm::dvec3& b);

struct PlateSpec {
  const Crystal* crystal = nullptr;
  glm::dmat3 crystal_to_lab{1.0};  // columns: crystal X, Y, Z in the lab; stage rotation applied
  double thickness_um = 30.0;
  double n_outside = 1.54;  // medium on both faces (mounting medium)
  bool fresnel = true;      // include the interface transmission amplitudes at both faces
};

// Everything of a plate that depends on the wavelength but not on the direction, so that a
// renderer evaluating many directions at one wavelength pays for the dispersion formulas once.
struct PreparedPlate {
  glm::dmat3 eta{1.0};                   // impermeability tensor ε⁻¹ in the lab frame (real, symmetric)
  glm::dmat3 mu_tensor{0.0};             // absorption tensor Σ μ_k·axis_k·axis_kᵀ (per µm)
  glm::dvec3 optic_axis{0.0, 0.0, 1.0};  // lab-frame Z (optical activity uses it; uniaxial)
  glm::dvec3 n_principal{1.5};
  double k0_per_um = 0.0;  // 2π/λ
  double thickness_um = 30.0;
  double n_outside = 1.54;
  double rho_rad_per_um = 0.0;  // rotatory power along the optic axis (signed, + dextrorotatory)
  double mean_n = 1.5;          // nβ (start of the biaxial iteration)
  CrystalSymmetry symmetry = CrystalSymmetry::Isotropic;
  bool fresnel = true;
  bool absorbing = false;
};
PreparedPlate prepare_plate(const PlateSpec& plate, double wavelength_nm);

struct PlateModes {       // the two eigenmodes inside the plate for that wave
  double n1, n2;          // effective refractive indices (n1 ≤ n2: n2 is the slow wave)
  glm::dvec3 e1, e2;      // their field directions projected to the transverse plane of k_air (unit)
  double retardation_nm;  // Γ = d·(k_z2 − k_z1)/k0: optical path difference slow − fast (≥ 0)
  double t1, t2;          // amplitude transmissions (both faces × absorption) of a wave polarized
                          // along e1 (e2) through that mode alone; 1 − R per face at normal incidence
  // Extra detail (same wave):
  glm::dvec3 s1, s2;              // unit wave normals inside the crystal
  double kz1, kz2;                // normal wave-vector components in units of k0 (k_z = n·s_z)
  double mean_phase_rad;          // k0·d·(k_z1 + k_z2)/2: the common phase plate_jones removes
  glm::dvec3 walkoff1, walkoff2;  // lateral ray displacement across the plate (µm), from the
                                  // Poynting directions; plate_jones neglects it (see plate.cpp)
};
PlateModes plate_modes(const PlateSpec& plate, const glm::dvec3& k_air, double wavelength_nm);
PlateModes plate_modes(const PreparedPlate& plate, const glm::dvec3& k_air);

// Jones matrix of the plate for a plane wave travelling along k_air (direction in air, unit,
// k.z > 0) at wavelength_nm, expressed in transverse_basis(k_air) before and after (the direction
// after equals the one before). The common propagation phase k0·d·(k_z1 + k_z2)/2 is removed;
// only the relative phase ±k0·d·(k_z2 − k_z1)/2 of the two modes remains. No allocation, no
// virtual call in the PreparedPlate overload (the PlateSpec one evaluates the dispersion first).
// k_air must be a unit vector with √(k.x² + k.y²) < n_outside.
JonesMatrix plate_jones(const PlateSpec& plate, const glm::dvec3& k_air, double wavelength_nm);
JonesMatrix plate_jones(const PreparedPlate& plate, const glm::dvec3& k_air);

}  // namespace pmsim
