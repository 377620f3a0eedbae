#include "core/ebsd/point_count.h"

#include <string>

#include "core/base/json_reader.h"

namespace pmsim {

void check_point_count(const MapText& t, double promised) {
  if (promised < 1.0 || promised > kMaxMapPoints)
    t.fail_header("point count", "the header promises " + number_text(promised) +
                                     " points; a map must have 1 to 10^8 points");
}

void finish_point_count(OrientationMap& m, std::size_t held, const char* header_terms) {
  m.points_in_file = held;
  if (held < m.size())
    m.warnings.push_back(m.file + ": the header promises " + std::to_string(m.size()) + " points (" +
                         header_terms + ") but the file holds " + std::to_string(held) +
                         "; the missing " + std::to_string(m.size() - held) + " points are non-indexed");
}

}  // namespace pmsim
