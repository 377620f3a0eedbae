#pragma once
// The readers place points by their order in the file (row by row, x fastest: both vendors write
// them so) and compare each point's written x, y with that grid position. A mismatch (rows deleted
// in the middle of a file, a map written column by column) is reported once as a warning naming
// the first line where it happens: the map still loads, but shows where it went wrong.
#include <cstddef>
#include <string>

#include "core/ebsd/orientation_map.h"

namespace pmsim {

class PositionCheck {
 public:
  // Point i written at (x_um, y_um) on line `line` of the file.
  void check(const OrientationMap& m, std::size_t i, double x_um, double y_um, std::size_t line) {
    if (mismatch_line_ != 0) return;
    const double dx = x_um - m.origin_x_um - m.x_um(i), dy = y_um - m.origin_y_um - m.y_um(i);
    // Half a step: written positions are rounded to a few decimals, far less than a step.
    if (dx * dx > 0.25 * m.step_x_um * m.step_x_um || dy * dy > 0.25 * m.step_y_um * m.step_y_um) {
      mismatch_line_ = line;
      x_ = x_um, y_ = y_um, gx_ = m.origin_x_um + m.x_um(i), gy_ = m.origin_y_um + m.y_um(i);
    }
  }
  void report(OrientationMap& m) const;

 private:
  std::size_t mismatch_line_ = 0;
  double x_ = 0, y_ = 0, gx_ = 0, gy_ = 0;
};

}  // namespace pmsim
