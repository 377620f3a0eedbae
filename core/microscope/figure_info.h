#pragma once
// What the interference figure of the sample under the field centre is, for the teaching panel:
// uniaxial or biaxial, 2V, optic sign, how the crystal is cut relative to the microscope axis, and
// what the compensator (slow direction NE–SW) shows for that sign.
#include <string>

#include "core/microscope/scene.h"

namespace pmsim {

struct FigureInfo {
  std::string mineral;
  std::string kind;            // "uniaxial", "biaxial", "isotropic", "opaque", "empty stage"
  std::string optic_sign;      // "positive", "negative", "" (isotropic)
  double two_v_deg = 0.0;      // biaxial: 2V about the acute bisectrix; uniaxial 0
  double axis_tilt_deg = 0.0;  // optic axis (uniaxial) / acute bisectrix (biaxial) from the microscope axis
  std::string orientation;     // e.g. "centred optic-axis figure", "acute bisectrix figure", "flash figure"
  std::string
      compensator;  // what the accessory shows, e.g. "addition (blue) in the NE and SW quadrants → positive"
  std::string summary;  // one line with all of the above
};

// Throws InputError for an invalid scene.
FigureInfo describe_figure(const Scene& scene);

}  // namespace pmsim
