#pragma once
// Colour conversions: XYZ → linear sRGB → 8-bit sRGB (IEC 61966-2-1:1999), CIELAB (CIE 15:2004
// §8.2.1) and the CIEDE2000 colour difference (CIE 142-2001; Sharma, Wu, Dalal 2005).
#include <cstdint>
#include <glm/vec3.hpp>

namespace pmsim {

glm::dvec3 xyz_to_linear_srgb(const glm::dvec3& xyz);
glm::dvec3 linear_srgb_to_xyz(const glm::dvec3& rgb);
double srgb_encode(double linear);  // IEC 61966-2-1 transfer function, input in [0,1]
double srgb_decode(double encoded);
// Clips to [0,1] per channel in linear RGB, then encodes and rounds; NaN maps to 0.
std::uint8_t linear_to_srgb8(double linear);

// CIELAB lightness L* = 116 f(Y/Yn) − 16 (CIE 15:2004 §8.2.1) of a relative luminance Y/Yn.
double cielab_lightness(double Y_relative);
glm::dvec3 xyz_to_lab(const glm::dvec3& xyz, const glm::dvec3& white_xyz);
double ciede2000(const glm::dvec3& lab1, const glm::dvec3& lab2);

}  // namespace pmsim
