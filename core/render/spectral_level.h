#pragma once
// One level of the spectral quadrature: the visible range 380–780 nm cut into n equal bands, each
// evaluated at its centre. Each band carries the exact integral of the observer weights over it,
// so that T ≡ 1 gives the reference white at any n (the exposure never depends on the sampling),
// and the modal plate model averages the interference terms over the band (no aliasing).
#include <array>
#include <vector>

#include <glm/vec3.hpp>

#include "core/crystal/plate.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/optical_train.h"

namespace pmsim {

struct SpectralLevel {
  int n = 0;
  bool monochromatic = false;  // render.single_wavelength_nm: one line, weight 1
  double band_nm = 0.0;
  std::vector<double> nm;
  std::vector<glm::dvec3> weight;  // W = ∫_band S·(x̄,ȳ,z̄) dλ / ∫ S·ȳ dλ
  std::vector<glm::dvec3> moment;  // M = ∫_band w(λ)·(λ − λc) dλ (the weights' slope)
  std::vector<std::array<double, 3>> anchor_w, anchor_dw;  // modal anchor weights at λc (and d/dλ)
  std::vector<TrainState> train;
  // The exact plates of the domains that exact units show, [band][slot], slot = prepared_slot[domain]
  // (−1: not prepared, prepare_plate on demand). Only those: of an EBSD map's 10⁴ domains only the
  // absorbing and near-axis optically active ones are exact, and plates for all of them at every
  // band (and the 40 MB of their storage) took most of the map's first image.
  std::vector<std::vector<PreparedPlate>> prepared;
  std::vector<int> prepared_slot;
  // The prepared plate of `domain` at band `band`, or null.
  const PreparedPlate* plate(int band, int domain) const {
    const int s = domain < static_cast<int>(prepared_slot.size()) ? prepared_slot[domain] : -1;
    return s >= 0 ? &prepared[band][s] : nullptr;
  }
  // The modal kernel's per-band constants, laid out for vector loops over the bands: 1/λc, the
  // anchor weights and their slopes, and M·6/h; `steady[a]` = Σ_bands W·w_a + M·dw_a, the whole
  // non-oscillating term C0 of every band in one product per anchor.
  std::vector<double> inv_nm, aw[3], adw[3];
  std::vector<glm::dvec3> moment6h;
  glm::dvec3 steady[3]{};
};

SpectralLevel make_spectral_level(const EvaluationPlan& plan, int n);

// The same bands (and prepared plates) in another polarizing train: what make_spectral_level
// gives on the plan of `scene`, a scene that differs from the plan's only in the polars and the
// accessory. Exact units evaluated with it see that train.
SpectralLevel level_in_train(const SpectralLevel& level, const Scene& scene, const CompensatorPlate& compensator);

// Spectral transmittance of one unit at band i with the exact plate Jones matrix (band centre).
double unit_transmission(const EvaluationPlan& plan, const SpectralLevel& level, int unit, int band);
// XYZ of one unit (Y = 1: the exposure reference); monochromatic: (T, T, T).
glm::dvec3 evaluate_unit(const EvaluationPlan& plan, const SpectralLevel& level, int unit);

// One unit in several polarizing trains at once (no compensator in any): xyz[t] is what
// evaluate_unit gives on the plan of trains[t]. The plan must keep its fits (modal_fits()). The
// modal band sum is Σ_a steady[a]·C0[a] + Σ_a Cφ[a]·S_a, where
// S_a = Σ_bands w_a·(W·cos φ·sinc − M·6/h·sin φ·q) depends on the fit's Γ alone (modal_plain_xyz's
// sum regrouped by anchor): the band loop runs once a direction, each train costs its terms
// (make_modal_terms) and a few products. Only for units shares_band_loop accepts (modal, bands,
// no compensator, at most 256 bands).
bool shares_band_loop(const EvaluationPlan& plan, const SpectralLevel& level, int unit);
void evaluate_unit_in_trains(const EvaluationPlan& plan, const SpectralLevel& level, int unit,
                             const std::vector<TrainState>& trains, glm::dvec3* xyz);

// One unit in another polarizing train, an accessory's included: what evaluate_unit gives on the
// plan of a scene that differs from the plan's only in the polars and the accessory. `L` holds that
// train per band (level_in_train, or trains turned by train_in_specimen_frame), `train` the same
// train at 550 nm (the modal terms' directions, as the plan's own). Modal units from their fits (the
// plan must keep them: compile_evaluation_plan's keep_fits), exact ones band by band in L's trains.
glm::dvec3 evaluate_unit_in_train(const EvaluationPlan& plan, const SpectralLevel& L, const TrainState& train, int u);

}  // namespace pmsim
