#pragma once
// What the tables of modal fits (radial for a plate ⟂ its optic axis, over the direction for any
// plate) are checked against: the same plan with every unit fitted from its own three mode
// solutions, and the mean CIEDE2000 between the images two plans develop.
#include <vector>

#include "core/microscope/evaluation_plan.h"
#include "core/render/image_develop.h"
#include "core/render/spectral_level.h"

namespace pmsim::test {

// The same set-up with every unit fitted from its own three mode solutions (the general path).
inline EvaluationPlan per_direction_fits(const EvaluationPlan& plan) {
  std::vector<ModalTerms> terms = plan.modal_terms();
  const TrainState train = make_train(plan.scene(), plan.compensator(), 550.0);
  PreparedPlate anchors[3];
  for (int a = 0; a < 3; ++a) anchors[a] = plan.prepare(0, ModalFit::kAnchorNm[a]);
  for (std::size_t u = 0; u < plan.units().size(); ++u) {
    ModalFit fit;
    fit.fit(anchors, plan.units()[u].k_air);
    glm::dmat2 c, o;
    plan.lens_jones(plan.units()[u].k_air, c, o);
    terms[u] = make_modal_terms(fit, train, 1.0, &c, &o);
  }
  return plan.with_modal_terms(std::move(terms));
}

inline double image_difference(const EvaluationPlan& A, const EvaluationPlan& B, int bands) {
  const SpectralLevel LA = make_spectral_level(A, bands), LB = make_spectral_level(B, bands);
  std::vector<glm::dvec3> ua(A.units().size()), ub(B.units().size());
  for (std::size_t u = 0; u < ua.size(); ++u) {
    ua[u] = evaluate_unit(A, LA, static_cast<int>(u));
    ub[u] = evaluate_unit(B, LB, static_cast<int>(u));
  }
  RenderImage ia, ib;
  develop_image(A, ua, false, ia);
  develop_image(B, ub, false, ib);
  return mean_ciede2000(A, ia.xyz, ib.xyz);
}

}  // namespace pmsim::test
