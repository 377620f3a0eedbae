#pragma once
// Jones calculus for fully polarized light (Born & Wolf §10.8; Hecht §8.12). A JonesVector holds
// the complex transverse field in a 2-D basis that the caller names; a JonesMatrix maps one such
// field to another. Used where rays of one source and wavelength are summed coherently.
// Basis and sign conventions: docs/conventions.md.
#include <complex>

#include <glm/mat2x2.hpp>

namespace pmsim {

using complexd = std::complex<double>;

struct JonesVector {
  complexd x{0.0}, y{0.0};
  double intensity() const { return std::norm(x) + std::norm(y); }
  JonesVector operator+(const JonesVector& o) const { return {x + o.x, y + o.y}; }
  JonesVector operator*(complexd s) const { return {x * s, y * s}; }
};

struct JonesMatrix {
  // Row-major: out.x = xx*in.x + xy*in.y ; out.y = yx*in.x + yy*in.y
  complexd xx{1.0}, xy{0.0}, yx{0.0}, yy{1.0};
  static JonesMatrix identity() { return {}; }
  static JonesMatrix zero() { return {0.0, 0.0, 0.0, 0.0}; }
  JonesVector operator*(const JonesVector& v) const { return {xx * v.x + xy * v.y, yx * v.x + yy * v.y}; }
  // this * o : apply o first, then this.
  JonesMatrix operator*(const JonesMatrix& o) const {
    return {xx * o.xx + xy * o.yx, xx * o.xy + xy * o.yy, yx * o.xx + yy * o.yx, yx * o.xy + yy * o.yy};
  }
  JonesMatrix operator*(complexd s) const { return {xx * s, xy * s, yx * s, yy * s}; }
  JonesMatrix operator+(const JonesMatrix& o) const { return {xx + o.xx, xy + o.xy, yx + o.yx, yy + o.yy}; }
};

// A real 2×2 matrix (a lens' frame change or diattenuation) as a Jones matrix. glm is
// column-major (m[column][row]), JonesMatrix row-major: xx = m[0][0], xy = m[1][0], yx = m[0][1].
inline JonesMatrix jones_from_real(const glm::dmat2& m) { return {m[0][0], m[1][0], m[0][1], m[1][1]}; }

// Linear polarizer (ideal) whose transmission axis is at angle_rad from the basis x axis.
inline JonesMatrix linear_polarizer(double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  return {c * c, c * s, c * s, s * s};
}

// Rotation of the field by angle_rad (counter-clockwise, as seen looking against the light).
inline JonesMatrix rotation(double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  return {c, -s, s, c};
}

}  // namespace pmsim
