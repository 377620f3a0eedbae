#pragma once
// A compensator's band sums, kept per modal direction (issue 21: every frame of a conoscopic figure
// with the gypsum plate, the mica plate or the quartz wedge in the slot, at any stage and polars).
//
// The general band loop (spectral_level.cpp, modal_general_xyz) is, per direction,
//   XYZ = Σ_bands [W·c0 + M·c0′] + Σ_k c_k(λ)·osc(ϑ_k),  c_k(λ) = Σ_a w_a(λ)·C[k][a],
// with the terms of make_modal_terms (k: cos φ, cos χ, cos(φ+χ), cos(φ−χ); a: the fit's three
// anchors; osc the band-averaged cosine of band_integral.h). Regrouped by term and anchor,
//   XYZ = Σ_a C[0][a]·steady[a] + Σ_k Σ_a C[k][a]·S_k[a],   S_k[a] = Σ_bands w_a·osc(ϑ_k),
// where the sums S depend on the direction's retardation Γ (through φ) and on χ = 2πΓ_c/λ, the
// accessory's phase at its wedge position, but not on the polars, the slot's angle or the stage,
// which enter only the coefficients C (train_in_specimen_frame turns directions, not phases). So
// one general band loop per direction for an accessory state serves every frame with it: a frame
// is then make_modal_terms and 15 products a direction. The steady and cos χ sums are the same for
// every direction; each direction keeps its φ, φ+χ and φ−χ sums (27 floats).
#include <atomic>
#include <vector>

#include <glm/vec3.hpp>

#include "core/render/spectral_level.h"

namespace pmsim {

struct CompensatorSums {
  glm::dvec3 steady[3]{};    // Σ_bands W·w_a + M·w_a′ (C0)
  glm::dvec3 chi[3]{};       // Σ_bands w_a·osc(χ) (Cχ)
  std::vector<float> dirs;   // per plan direction (unit·dirs_per_unit + d): [φ, φ+χ, φ−χ][anchor][XYZ]
};

// The sums of every modal direction of `plan` at the bands of `L`, a level in a train with the
// accessory (level_in_train): exact units are skipped (they go band by band). The plan must keep
// its fits. Empty `dirs` when cancelled.
CompensatorSums compensator_sums(const EvaluationPlan& plan, const SpectralLevel& L,
                                 const std::atomic<bool>* cancel = nullptr);

// What evaluate_unit_in_train gives for unit u in `train` (the 550 nm train of L's, with the
// accessory whose sums `sums` holds, turned or not): modal units from their sums, exact ones band
// by band in L's trains.
glm::dvec3 evaluate_unit_from_sums(const EvaluationPlan& plan, const SpectralLevel& L, const TrainState& train,
                                   const CompensatorSums& sums, int u);

}  // namespace pmsim
