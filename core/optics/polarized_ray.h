#pragma once
// The ray of the paper (Debelov, Kushner, Vasilyeva, §6): Ray = <R, Payload>, R = <P, dir>,
// Payload = <λ, I(λ), v_p, δ, O_p, ch>. The field it carries is √I · v_p · e^(−iδ) (plus the
// propagation phase 2π·O_p/λ that the application adds), v_p a unit vector ⟂ dir.
#include <glm/vec3.hpp>

namespace pmsim {

struct PolarizedRay {
  glm::dvec3 origin{0.0};
  glm::dvec3 dir{0.0, 0.0, 1.0};  // unit
  double wavelength_nm = 550.0;   // λ in vacuum
  double intensity = 1.0;         // I(λ)
  glm::dvec3 pol{1.0, 0.0, 0.0};  // v_p: unit, ⟂ dir
  double delta_rad = 0.0;         // δ: jump-wise phase (TIR); the paper's dφ = 2π·O_p/λ − δ
  double optical_path_mm = 0.0;   // O_p = Σ n·S, kept in double so long paths keep their phase
  int source = 0;                 // ch: coherence id, passed through untouched
  int depth = 0;                  // internal reflections met inside the last lens
};

}  // namespace pmsim
