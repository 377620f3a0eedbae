#include "core/ebsd/grid_position_check.h"

#include "core/base/json_reader.h"

namespace pmsim {

void PositionCheck::report(OrientationMap& m) const {
  if (mismatch_line_ == 0) return;
  m.warnings.push_back(m.file + ": line " + std::to_string(mismatch_line_) + " puts its point at x = " +
                       number_text(x_) + ", y = " + number_text(y_) + " µm where the header's grid has (" +
                       number_text(gx_) + ", " + number_text(gy_) +
                       "); points are placed by their order in the file");
}

}  // namespace pmsim
