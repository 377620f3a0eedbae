#pragma once
// The estimate behind optics.lens_model = auto: how much the physical condenser and objective
// would change the image against ideal lenses.
#include "core/microscope/lens_polarization.h"

namespace pmsim {

class EvaluationPlan;

// Mean CIELAB lightness difference |ΔL*| at 550 nm between the ideal and the physical lens model
// (`table`) over a subset of the plan's units (about 512, up to 8 directions of each). The lenses
// only change polarization and transmission (not the spectrum), so the grey-level difference at
// mid-spectrum is their effect. Uses the plan's domains, units and compensator, not its lenses.
double lens_model_difference(const EvaluationPlan& plan, const LensPolarizationTable& table);

}  // namespace pmsim
