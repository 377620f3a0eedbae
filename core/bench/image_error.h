#pragma once
// Per-pixel colour error of a rendered image against a reference: CIEDE2000 (CIE 142-2001) of
// the two CIELAB colours, white = the scene illuminant with Y = 1 (the exposure reference), over
// the lit pixels only (outside the conoscopic disk both images are black by construction).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace pmsim {

struct ImageError {
  double mean_de2000 = 0.0;
  double p95_de2000 = 0.0;  // 95th percentile
  double max_de2000 = 0.0;
  std::size_t pixels = 0;  // lit pixels compared
};

// xyz_*: width·height·3 floats (CIE XYZ, Y = 1 white). lit: width·height bytes, non-zero for a
// pixel to count (empty: all pixels). A non-finite value makes that pixel's error +∞, so that a
// NaN can never hide in a mean.
ImageError image_error_de2000(const std::vector<float>& xyz_test, const std::vector<float>& xyz_ref,
                              const std::vector<std::uint8_t>& lit, const glm::dvec3& white_xyz);

}  // namespace pmsim
