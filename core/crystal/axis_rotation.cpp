#include "core/crystal/axis_rotation.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace pmsim {

glm::dmat3 axis_rotation(const glm::dvec3& u, double theta_rad) {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  glm::dmat3 r(0.0);  // r[column][row]
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) r[col][row] = (1.0 - c) * u[row] * u[col] + (row == col ? c : 0.0);
  r[1][0] -= s * u.z, r[0][1] += s * u.z;  // [u]× = ((0, −z, y), (z, 0, −x), (−y, x, 0)) by rows
  r[2][0] += s * u.y, r[0][2] -= s * u.y;
  r[2][1] -= s * u.x, r[1][2] += s * u.x;
  return r;
}

glm::dmat3 rotation_taking(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 k = glm::cross(a, b);
  const double sin_t = glm::length(k);
  if (!(sin_t > 1e-12)) return glm::dmat3(1.0);
  return axis_rotation(k / sin_t, std::atan2(sin_t, glm::dot(a, b)));
}

}  // namespace pmsim
