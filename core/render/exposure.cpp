#include "core/render/exposure.h"

#include <cmath>

namespace pmsim {

double exposure_gain(double ev) { return std::exp2(ev); }

std::vector<float> exposed(const std::vector<float>& rgb_linear, double ev) {
  std::vector<float> out(rgb_linear);
  if (ev == 0.0) return out;
  const float g = static_cast<float>(exposure_gain(ev));
  for (float& v : out) v *= g;
  return out;
}

}  // namespace pmsim
