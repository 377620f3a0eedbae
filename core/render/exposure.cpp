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

glm::dmat3 display_matrix(double ev, ColourVision vision) {
  return exposure_gain(ev) * colour_vision_matrix(vision);
}

std::vector<float> displayed(const std::vector<float>& rgb_linear, double ev, ColourVision vision) {
  if (vision == ColourVision::Normal) return exposed(rgb_linear, ev);
  const glm::dmat3 m = display_matrix(ev, vision);
  std::vector<float> out(rgb_linear.size());
  for (std::size_t i = 0; i + 2 < rgb_linear.size(); i += 3) {
    const glm::dvec3 v = m * glm::dvec3(rgb_linear[i], rgb_linear[i + 1], rgb_linear[i + 2]);
    out[i] = float(v.x);
    out[i + 1] = float(v.y);
    out[i + 2] = float(v.z);
  }
  return out;
}

}  // namespace pmsim
