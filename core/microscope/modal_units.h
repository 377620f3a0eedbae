#pragma once
// The modal stage of an evaluation plan: for every unit and direction the plate's modal fit
// (core/microscope/modal_fit.h) reduced to its interference terms in the polarizing train, and
// which units the ExactnessCriteria send to the exact Jones matrix instead.
#include <atomic>
#include <optional>
#include <vector>

#include "core/microscope/modal_fit.h"
#include "core/microscope/model_policy.h"

namespace pmsim {

class EvaluationPlan;
struct EvalUnit;
struct OpticalDomain;

// How many times the domain's fitted thickness a unit is (a wedge's steps): the scale
// make_modal_terms applies to its fit. 1 where the unit shows no crystal.
double modal_thickness_scale(const EvalUnit& unit, const OpticalDomain& domain);

struct ModalUnits {
  std::vector<ModalTerms> terms;  // unit u, direction d at u*dirs_per_unit+d
  // The fits themselves, indexed as `terms` (fit_modal_units' `keep_fits`; a unit without a
  // crystal holds the identity's), for terms in other polarizing trains: a fit costs three plate
  // solutions, its terms in a train a few products.
  std::vector<ModalFit> fits;
  int dirs_per_unit = 1;
  std::vector<char> unit_exact;  // 1 = this unit needs the exact Jones matrix
  bool radial_table = false;     // the fits came from a RadialModalTable
  bool direction_table = false;  // the fits came from a DirectionModalTable
};

// Fits every unit of `plan` (its domains, view and lenses set) in parallel (TBB); nullopt when
// `cancel` (may be null) is raised meanwhile. A conoscopic figure of one uniaxial domain with its
// optic axis along the stage normal takes its fits from a radial table.
std::optional<ModalUnits> fit_modal_units(const EvaluationPlan& plan, const ExactnessCriteria& exact,
                                          const std::atomic<bool>* cancel = nullptr, bool keep_fits = false);

}  // namespace pmsim
