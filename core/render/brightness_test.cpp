#include "core/render/brightness_test.h"

#include <cmath>
#include <stdexcept>

#include "core/microscope/compensator.h"
#include "core/render/michel_levy_chart.h"

namespace pmsim {

BrightnessTest brightness_test(double retardation_nm, Compensator accessory, Illuminant illuminant) {
  if (accessory != Compensator::Gypsum && accessory != Compensator::Mica)
    throw std::invalid_argument("brightness_test: the gypsum or the mica plate");
  BrightnessTest t;
  t.accessory = accessory;
  t.retardation_nm = retardation_nm;
  t.accessory_nm = compensator_retardation_nm(make_compensator(accessory, 0.0), 550.0);
  // Retardations add along parallel slow directions and subtract along crossed ones; the sign of
  // a difference does not matter to the colour (Γ and −Γ give the same intensity).
  t.y_alone = michel_levy_xyz(retardation_nm, illuminant).y;
  t.y_addition = michel_levy_xyz(retardation_nm + t.accessory_nm, illuminant).y;
  t.y_subtraction = michel_levy_xyz(std::abs(retardation_nm - t.accessory_nm), illuminant).y;
  const double d = t.y_addition - t.y_subtraction;
  t.reading = std::abs(d) < kBrightnessDifference ? "undecided"
              : d > 0                             ? "brighter on addition"
                                                  : "brighter on subtraction";
  return t;
}

}  // namespace pmsim
