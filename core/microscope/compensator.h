#pragma once
// The accessory slot above the objective: a retarder at 45° whose slow direction runs NE–SW
// (as on most instruments). Real dispersive plates built from the mineral library:
//  - gypsum first-order red: a (010) cleavage plate (nα and nγ in its plane), Γ(550 nm) = 550 nm;
//  - mica λ/4: a muscovite (001) cleavage sheet (nβ and nγ in its plane), Γ(550 nm) ≈ 147 nm
//    (the "λ/4" of sodium light the accessories are sold as, ~147 nm after Nesse 2012 §7);
//  - quartz wedge: quartz cut parallel to c, thickness growing with compensator_position 0…1 up
//    to Γ(550 nm) = 4 × 550 nm (four orders).
#include "core/crystal/plate.h"
#include "core/microscope/scene.h"

namespace pmsim {

struct CompensatorPlate {
  bool present = false;
  PlateSpec spec;                      // normal incidence, no Fresnel (cemented between glasses)
  double design_retardation_nm = 0.0;  // Γ at 550 nm
};

CompensatorPlate make_compensator(Compensator kind, double position);

// Retardation Γ(λ) (nm) and the unit slow direction (lab, in the stage plane) of the accessory.
double compensator_retardation_nm(const CompensatorPlate& c, double wavelength_nm);

}  // namespace pmsim
