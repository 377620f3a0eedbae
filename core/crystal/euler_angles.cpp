#include "core/crystal/euler_angles.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/base/units.h"

namespace pmsim {

namespace {

double wrap_2pi(double a) {
  a = std::fmod(a, 2.0 * kPi);
  return a < 0.0 ? a + 2.0 * kPi : a;
}

}  // namespace

glm::dmat3 crystal_to_sample_from_bunge(const EulerBunge& e) {
  const double c1 = std::cos(e.phi1_rad), s1 = std::sin(e.phi1_rad);
  const double c = std::cos(e.Phi_rad), s = std::sin(e.Phi_rad);
  const double c2 = std::cos(e.phi2_rad), s2 = std::sin(e.phi2_rad);
  // Rows of g (Bunge 1982 eq. 2.38) = crystal axes in the specimen frame = columns of gᵀ.
  const glm::dvec3 e1{c1 * c2 - s1 * s2 * c, s1 * c2 + c1 * s2 * c, s2 * s};
  const glm::dvec3 e2{-c1 * s2 - s1 * c2 * c, -s1 * s2 + c1 * c2 * c, c2 * s};
  const glm::dvec3 e3{s1 * s, -c1 * s, c};
  return glm::dmat3(e1, e2, e3);
}

EulerBunge bunge_from_crystal_to_sample(const glm::dmat3& m) {
  const glm::dmat3 id = glm::transpose(m) * m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::abs(id[i][j] - (i == j ? 1.0 : 0.0)) > 1e-6)
        throw std::invalid_argument("orientation matrix is not orthonormal");
  if (glm::determinant(m) < 0.0) throw std::invalid_argument("orientation matrix is a reflection (det < 0)");
  // g_ij = m[i][j] (row i of g is column i of m): g33 = cos Φ, g31 = s1 sΦ, g32 = −c1 sΦ,
  // g13 = s2 sΦ, g23 = c2 sΦ.
  const double g33 = std::clamp(m[2][2], -1.0, 1.0);
  EulerBunge e;
  const double sPhi = std::hypot(m[2][0], m[2][1]);
  e.Phi_rad = std::atan2(sPhi, g33);
  if (sPhi > 1e-9) {
    e.phi1_rad = wrap_2pi(std::atan2(m[2][0], -m[2][1]));
    e.phi2_rad = wrap_2pi(std::atan2(m[0][2], m[1][2]));
  } else {
    // Φ = 0: g11 = cos(φ1 + φ2), g12 = sin(φ1 + φ2); Φ = π: g11 = cos(φ1 − φ2), g12 = sin(φ1 − φ2).
    e.phi1_rad = wrap_2pi(std::atan2(m[0][1], m[0][0]));
    e.phi2_rad = 0.0;
  }
  return e;
}

}  // namespace pmsim
