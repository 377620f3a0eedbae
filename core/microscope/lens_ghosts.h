#pragma once
// Ghost light of the physical lens model (optics.lens_depth = dT ≥ 2): light that is reflected
// twice (4, …) inside the condenser or objective SML lens and still leaves it toward the image.
// It leaves in another direction than the main (depth-0) path, so in the conoscopic view it lands
// elsewhere in the back focal plane: a faint (≈ R² ≈ 0.2 % for N-BK7) re-mapped copy of the
// figure laid over it.
//
// Traced once per (dT, Fresnel model) with trace_lens at 550 nm from the specimen point (the
// lens' focus) for sin θ over [0, 0.999] and both eigen-polarizations s, p (rotational symmetry:
// a meridional ray stays meridional, one profile serves every azimuth). A ghost's exit direction
// is placed in the back focal plane with the same ρ = sin θ / NA mapping as the direct light.
// Objective ghosts: the light of one source direction ch (after condenser and sample) is carried
// along every ghost path; paths of the same ch landing in the same cell add as complex Jones
// amplitudes with phase 2π·O_p/λ − δ, their cross terms averaged over the spectral band
// (sinc(π·ΔO_p·Δλ/λ²)); different ch add in intensity. The cross term with the direct light
// itself (ΔO_p ≥ 2× the lens thickness ≈ 23 mm ≫ λ²/Δλ) averages to zero over any band and is
// left out. Condenser ghosts: the condenser is the objective mirrored through the specimen plane,
// so by reciprocity (Stokes relations) a ray reaching the specimen along k through a ghost path
// came from the aperture direction where the objective's path from k exits, with the same s/p
// amplitudes; the lit aperture (condenser NA) has uniform radiance, which the path conserves
// (radiance theorem) up to its throughput.
#include <atomic>
#include <vector>

#include <glm/vec3.hpp>

#include "core/optics/interface_model.h"

namespace pmsim {

class EvaluationPlan;

struct LensGhostPath {
  glm::dvec3 dir{0.0, 0.0, 1.0};  // exit direction, meridional plane y = 0 (azimuth 0)
  glm::dvec3 field_s{
      0.0};  // √I·pol leaving for a unit s input (pol ŷ), relative to the axial depth-0 amplitude
  glm::dvec3 field_p{0.0};                      // the same for a unit p input (p = s × k)
  double optical_path_mm = 0.0;                 // O_p through the lens
  double delta_s_rad = 0.0, delta_p_rad = 0.0;  // TIR phase jumps met (δ)
  int depth = 2;
};

struct LensGhostTable {
  static constexpr int kSamples = 256;
  double max_sin = 0.999;
  int depth = 0;
  std::vector<std::vector<LensGhostPath>> paths;  // [sample] at sin θ = max_sin·i/(kSamples−1)
  double axial_intensity = 1.0;                   // depth-0 transmission on the axis (normaliser)
  const std::vector<LensGhostPath>& at(double sin_theta) const;
};

// Cached per (depth, Fresnel model). Throws InputError if the lens asset is missing.
const LensGhostTable& lens_ghost_table(int depth, FresnelModel fresnel);

struct LensGhostImage {
  std::vector<float> xyz;         // width*height*3, added to the direct light (mono: T, T, T)
  double objective_energy = 0.0;  // Σ ghost intensity over the image, objective paths
  double condenser_energy = 0.0;  // the same, condenser paths
  int paths = 0;                  // ghost paths used
};

// The ghost light of a conoscopic (Bertrand in) plan with physical lenses and dT ≥ 2; empty xyz
// otherwise. Computed on a grid of at most ~128² source directions, bilinearly spread to pixels.
// A set `cancel` stops it between grid rows (the result is then incomplete: discard it).
LensGhostImage lens_ghost_image(const EvaluationPlan& plan, const std::atomic<bool>* cancel = nullptr);

}  // namespace pmsim
