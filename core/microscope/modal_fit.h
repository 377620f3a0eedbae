#pragma once
// A plate's eigenmodes for one direction across the whole visible range from three exact
// evaluations: quadratic Lagrange interpolation in x = 1/λ² (the Cauchy variable, in which
// dispersion is nearly linear) of Γ, the mode directions and transmissions. The fast-varying part
// of the response — the phase 2πΓ/λ — is then evaluated exactly at any wavelength, so a figure
// needs three mode solutions per pixel instead of one per wavelength.
#include <glm/mat2x2.hpp>

#include "core/crystal/plate.h"
#include "core/microscope/optical_train.h"

namespace pmsim {

struct ModalTerms;
struct TrainState;

class ModalFit {
 public:
  static constexpr double kAnchorNm[3] = {400.0, 520.0, 700.0};

  // anchors[i]: the plate prepared at kAnchorNm[i].
  void fit(const PreparedPlate anchors[3], const glm::dvec3& k_air);
  // The modes at wavelength_nm for a plate `thickness_scale` times as thick as the fitted one
  // (retardation ∝ thickness; transmissions as t^scale, absorption dominating thickness effects).
  ModalPoint at(double wavelength_nm, double thickness_scale = 1.0) const;
  double retardation_nm(double wavelength_nm) const;
  // A fit known otherwise (e.g. interpolated from a table of fits): Γ, the mode directions in
  // transverse_basis(k_air) and the transmissions at the three anchors.
  void assign(const double gamma_nm[3], const glm::dvec2 e1[3], const glm::dvec2 e2[3], const double t1[3],
              const double t2[3]);
  // The raw anchor values (what assign takes).
  double gamma_at_anchor(int a) const { return gamma_[a]; }
  const glm::dvec2& e1_at_anchor(int a) const { return e1_[a]; }
  const glm::dvec2& e2_at_anchor(int a) const { return e2_[a]; }
  double t1_at_anchor(int a) const { return t1_[a]; }
  double t2_at_anchor(int a) const { return t2_[a]; }

 private:
  friend ModalTerms make_modal_terms(const ModalFit&, const TrainState&, double, const glm::dmat2*,
                                     const glm::dmat2*);
  double gamma_[3]{};
  glm::dvec2 e1_[3], e2_[3];
  double t1_[3]{}, t2_[3]{};
};

// Mode directions of plate_modes as 2-D vectors in transverse_basis(k_air).
void modes_in_basis(const PlateModes& m, const glm::dvec3& k_air, glm::dvec2& e1, glm::dvec2& e2);

}  // namespace pmsim

namespace pmsim {

// The modal plate inside a fixed polarizing train, reduced to what varies with the wavelength:
// T(λ) = C0 + Cφ·cos φ + Cχ·cos χ + C₊·cos(φ+χ) + C₋·cos(φ−χ), φ = 2πΓ(λ)/λ the plate's phase
// difference and χ the compensator's. The coefficients are products of mode amplitudes (Jones
// calculus with the modes as basis), given at the three anchors and interpolated like Γ.
struct ModalTerms {
  double gamma_nm[3]{};
  double c[5][3]{};  // [C0, Cφ, Cχ, C₊, C₋][anchor]
};
// thickness_scale: the plate is that many times the fitted thickness (Γ ∝ d, t → t^scale).
// lens_in / lens_out: real Jones matrices of the condenser (before the sample) and the objective
// (after it) for this direction, in the ray's transverse basis; null = ideal lenses.
ModalTerms make_modal_terms(const ModalFit& fit, const TrainState& train, double thickness_scale = 1.0,
                            const glm::dmat2* lens_in = nullptr, const glm::dmat2* lens_out = nullptr);
// The identity sample's fit: no retardation, modes along the basis, full transmission (its terms
// in any train are identity_modal_terms').
ModalFit identity_modal_fit();
// The identity sample (empty stage, isotropic layer) in the same train.
ModalTerms identity_modal_terms(const TrainState& train, const glm::dmat2* lens_in = nullptr,
                                const glm::dmat2* lens_out = nullptr);

// Lagrange weights of the three anchors at wavelength_nm (value, and d/dλ).
void modal_anchor_weights(double wavelength_nm, double L[3], double dL_dnm[3]);

}  // namespace pmsim
