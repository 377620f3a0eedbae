#pragma once
// A polarization-exact path through a SpecimenScene, traced backward from the objective: each
// path carries complex transverse fields (a Jones vector in 3-D) instead of one linear vibration,
// and entering an anisotropic medium it splits into that medium's two eigenmodes, each refracted
// with its own index and carrying its own phase, so that the branches' coherent sum at the
// polarizer gives interference colours between crossed polars and the relief of each vibration.
//
// Events (at each interface the refracted light is followed, the reflected part counted and
// dropped, as in trace_specimen; under total internal reflection the reflected light is followed):
//  * Isotropic → isotropic, and a crystal mode → an isotropic medium (the mode seen as a wave of
//    its index n_k): exact complex Fresnel amplitudes (core/optics/fresnel.h) in the s/p frame,
//    power-normalized, τ = t·√(n_t cosθt / n_i cosθi), so |E|² is the transmitted power and
//    R + T = 1 per event; under TIR r_s, r_p carry the TIR phases (|r| = 1).
//  * Into a crystal: per mode k (fast, slow of the central section ⟂ the wave normal,
//    core/crystal/section_optics.h), the refracted wave normal t_k solves Snell's law with the
//    direction-dependent index n_k(t_k) (fixed-point iteration); the mode takes the incident
//    field's component along a_k = (e_k·s)s + (e_k·p_t)p_i (the mode's vibration e_k carried back
//    through the s/p frame) with the power transmittance of that linear vibration,
//    T_k = (e_k·s)²T_s + (e_k·p_t)²T_p, so R_k + T_k = 1 for each mode. The cross-coupling of
//    a mode's transmitted field into the other mode (t_s ≠ t_p at oblique incidence) is dropped:
//    second order in (t_s − t_p)·sinθ, ≈ 1e-4 at the angles of a microscope objective. A mode
//    that would be evanescent is dropped (its light reflected).
//  * TIR inside a crystal: the mirror direction, the reflected field split into the crystal's
//    modes at that direction (both taken along the mirror direction: the change of angle on mode
//    conversion is neglected).
//  * Bulk: phase k0·n·L in double (never wrapped, so retardations of thousands of waves stay
//    exact), pleochroic attenuation exp(−μ(e_k)·L/2) of the amplitude with μ(e) = Σ μ_i (e·axis_i)²
//    (crystal.h's principal_absorption_per_um). Wave normals are followed (walk-off neglected).
//  * Exit below the slide: each branch's field is projected on the polarizer (its vibration
//    projected ⟂ the branch) with the phase of a plane wave arriving along the branch,
//    −k0·n·(d·(x_exit − x_start)), which makes the branches' phase difference the one of a
//    tilted plate (exact for parallel faces). Branches leaving in the same direction add
//    coherently; those leaving in different directions with the coherence exp(−k0·L·|Δd|²)
//    (jones_path.cpp: 1 for a plate, fringes at a shallow wedge, intensities added for branches
//    that leave by other faces, which stand for other points of the incoherent source).
// Branch tree: at most kMaxJonesLeaves leaves; past that a split keeps only the stronger mode and
// the other's power is counted in InterfaceCounters::capped_power (a grain mount needs 2 leaves
// for a fragment, 4 after one TIR inside it; 8 is never reached in the tests' scenes).
//
// Reciprocity: for media without optical activity the backward Jones matrix is the transpose of
// the forward one, so ⟨p|J_forward|a⟩ is the bilinear product p·(J_backward a): tracing backward
// from the analyzer's vibration a gives the amplitude the polarizer's light reaches it with.

#include <array>

#include <glm/vec3.hpp>

#include "core/optics/mueller.h"

#include "core/specimen/specimen_scene.h"
#include "core/specimen/specimen_tracer.h"

namespace pmsim {

constexpr int kMaxJonesLeaves = 8;

struct JonesPathRequest {
  glm::dvec3 origin{0.0};      // in the air above the cover glass
  glm::dvec3 dir{0.0, 0.0, -1.0};  // pointing down (made unit)
  double wavelength_nm = 550.0;
  // Backward start vibrations (projected ⟂ dir and normalized): 1 = the analyzer's; 2 = two
  // orthogonal ones (analyzer out: I = Σ_a |⟨p|J|a⟩|², the whole power behind the polarizer).
  int starts = 1;
  glm::dvec3 start_vibration{1.0, 0.0, 0.0};  // the first; the second is dir × first
  glm::dvec3 polarizer{1.0, 0.0, 0.0};        // the polarizer's vibration (lab / specimen frame)
  double condenser_sin_max = 1.0;             // a branch is lit if it leaves with sinθ ≤ this
  int max_interfaces = 64;                    // per branch
  // Forward (core/specimen/forward_plane_light.h): the path starts in the air below the slide
  // going up with `start_vibration` (the polarizer's; starts = 1), and every branch that leaves
  // the cover glass upward with sinθ ≤ objective_sin_max is kept as an exit with its own point,
  // direction and power |E|² (analyzer out: the camera adds the branches' intensities).
  bool forward = false;
  double objective_sin_max = 1.0;
  // Forward with the analyzer in: each exit's field is projected on the analyzer's vibration
  // (lab / specimen frame, projected ⟂ the exit direction) and the exits of one path are summed
  // with their mutual coherence (as the backward lit branches): exit i's power is
  // |a_i|² + Σ_j≠i γ_ij Re(a_i a_j*), so that the powers add up to the coherent total and each
  // is splatted where its own branch lands (γ = 1 for a plate's two waves, which land together).
  bool forward_analyzer_in = false;
  glm::dvec3 forward_analyzer{0.0, 1.0, 0.0};
  // Forward, for the specimen response (forward_response.h): both input vibrations x and y (the
  // frame's), carried into the ray by the condenser's aplanatic map (aplanatic_map below), and
  // every exit keeps its Jones matrix, mapped back into the objective's collimated space; the
  // scoring (each exit's Mueller share) is the caller's. start_vibration, starts and the
  // forward analyzer are not used.
  bool forward_jones = false;
};

// The aplanatic map of a lens between its collimated space and a ray along unit d (up or down):
// the component along s = unit(ẑ × d) is kept, the one along p0 = s × ẑ becomes p = s × d
// (Richards & Wolf 1959; docs/physics.md). v is a vector of the collimated space (z = 0).
glm::dvec3 aplanatic_map(const glm::dvec3& v, const glm::dvec3& d);

// A forward path's branch leaving the cover glass toward the objective.
struct JonesExit {
  glm::dvec3 point{0.0};  // on the cover glass's top face
  glm::dvec3 dir{0.0};    // unit, up
  double power = 0.0;     // |E|², of the unit power that entered (analyzer in: see above; may be < 0)
  // forward_jones: the exit's Jones matrix (columns: input x, y; rows: output x, y of the
  // objective's collimated space), with the plane-wave phase of the branch at its exit point.
  Jones2 jones{};
};

struct JonesPath {
  // |⟨p|J|a_i⟩|² per start vibration, the lit branches summed with their mutual coherence.
  double power[2]{};
  int leaves = 0;                       // branches that ended (lit or not)
  int lit = 0;                          // branches that left below inside the condenser's cone
  int interfaces = 0;                   // Fresnel events over all branches
  std::array<JonesExit, kMaxJonesLeaves> exits{};  // forward: the branches the objective collects
  int n_exits = 0;
  // k0·L of the longest crystal path: exits e, f of one path interfere with the coherence
  // γ = exp(−k0·L·|d_e − d_f|²) (see the top of this file).
  double k0_crystal_um = 0.0;
  double intensity(int starts) const {
    return starts > 1 ? power[0] + power[1] : power[0];
  }
};

JonesPath trace_specimen_jones(const SpecimenScene& scene, const JonesPathRequest& request,
                               InterfaceCounters* counters = nullptr);

}  // namespace pmsim
