#pragma once
// The compensator test read by brightness instead of colour (issue 23, for students who cannot
// tell interference colours apart): with the grain at 45° between crossed polars, inserting an
// accessory adds its retardation when the grain's slow direction is parallel to the accessory's
// slow direction (NE–SW) and subtracts it when perpendicular (Nesse 2012 §7.7). The field's
// brightness — the luminance Y of the Michel-Lévy colour, which a dichromat sees as well as
// anyone — changes differently for the two: with the mica λ/4 plate (147 nm) a first-order grey
// brightens on addition and darkens on subtraction; with the gypsum plate (550 nm) a first-order
// grey turns to second-order blue on addition or first-order yellow on subtraction, nearly equal in
// luminance (a change of hue, not of brightness: the mica plate is the one to read by brightness).
// This says which way the brightness goes at a given retardation, and when it cannot tell (the two luminances within 0.05 of the field's white, about what an eye tells apart side
// by side, Weber fraction of a few per cent at these levels: Wyszecki & Stiles 1982, §7.10).
#include <string>

#include "core/microscope/scene.h"
#include "core/spectrum/illuminant.h"

namespace pmsim {

struct BrightnessTest {
  Compensator accessory = Compensator::Gypsum;
  double retardation_nm = 0.0;  // the grain's
  double accessory_nm = 0.0;    // the accessory's at 550 nm
  double y_alone = 0.0;         // Y of the grain at 45° (white field of the same light: 1)
  double y_addition = 0.0;      // with the accessory, slow ∥ slow
  double y_subtraction = 0.0;   // slow ⟂ slow
  std::string reading;          // "brighter on addition", "brighter on subtraction", or "undecided"
};

constexpr double kBrightnessDifference = 0.05;

// Gypsum or mica (the quartz wedge is read by moving it, not by one insertion); throws
// std::invalid_argument for another accessory.
BrightnessTest brightness_test(double retardation_nm, Compensator accessory, Illuminant illuminant = Illuminant::D65);

}  // namespace pmsim
