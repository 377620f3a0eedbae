#include "core/crystal/section_optics.h"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/base/units.h"

namespace pmsim {

namespace {
constexpr double kDeg = 180.0 / kPi;
}

SectionOptics section_optics(const glm::dmat3& axes, const glm::dvec3& n_xyz, const glm::dvec3& normal) {
  SectionOptics s;
  s.normal = glm::normalize(normal);
  // The indicatrix as a quadratic form r·B·r = 1 with B = A·diag(1/n²)·Aᵀ (A: columns X, Y, Z).
  const glm::dmat3 B = axes *
                       glm::dmat3(1.0 / (n_xyz.x * n_xyz.x), 0, 0, 0, 1.0 / (n_xyz.y * n_xyz.y), 0, 0, 0,
                                  1.0 / (n_xyz.z * n_xyz.z)) *
                       glm::transpose(axes);
  // Any orthonormal basis (u, v) of the section; the central section's ellipse is the 2×2 form
  // q = [u v]ᵀ B [u v], whose eigenvectors are its axes and eigenvalues 1/n′².
  const glm::dvec3 ref = std::abs(s.normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(ref - glm::dot(ref, s.normal) * s.normal);
  const glm::dvec3 v = glm::cross(s.normal, u);
  const double quu = glm::dot(u, B * u), qvv = glm::dot(v, B * v), quv = glm::dot(u, B * v);
  const double mean = 0.5 * (quu + qvv), half = std::hypot(0.5 * (quu - qvv), quv);
  const double l_fast = mean + half, l_slow = mean - half;  // larger 1/n² = smaller n = fast
  s.n_fast = 1.0 / std::sqrt(l_fast);
  s.n_slow = 1.0 / std::sqrt(l_slow);
  s.circular = s.n_slow - s.n_fast < 1e-12;
  // Eigenvector angle of the larger eigenvalue: tan 2φ = 2quv/(quu − qvv) (principal axes of a
  // symmetric 2×2 form).
  const double phi = 0.5 * std::atan2(2.0 * quv, quu - qvv);
  s.fast = std::cos(phi) * u + std::sin(phi) * v;
  s.slow = glm::cross(s.normal, s.fast);
  return s;
}

glm::dvec3 plane_trace(const glm::dvec3& section_normal, const glm::dvec3& plane_normal) {
  const glm::dvec3 t = glm::cross(section_normal, plane_normal);
  const double len = glm::length(t);
  if (!(len > 1e-12)) throw std::invalid_argument("the plane is parallel to the section: no trace");
  return t / len;
}

glm::dvec3 projected_direction(const glm::dvec3& section_normal, const glm::dvec3& direction) {
  const glm::dvec3 n = glm::normalize(section_normal);
  const glm::dvec3 p = direction - glm::dot(direction, n) * n;
  const double len = glm::length(p);
  if (!(len > 1e-12 * glm::length(direction)))
    throw std::invalid_argument("the direction is normal to the section: no projection");
  return p / len;
}

double line_angle_deg(const glm::dvec3& n, const glm::dvec3& from, const glm::dvec3& to) {
  const double a = std::atan2(glm::dot(glm::cross(from, to), glm::normalize(n)), glm::dot(from, to)) * kDeg;
  // Lines, not arrows: fold into (−90, 90].
  double r = std::fmod(a, 180.0);
  if (r > 90.0) r -= 180.0;
  if (r <= -90.0) r += 180.0;
  return r;
}

double trace_angle_deg(const glm::dvec3& t1, const glm::dvec3& t2) {
  const double c = std::abs(glm::dot(glm::normalize(t1), glm::normalize(t2)));
  return std::acos(std::min(1.0, c)) * kDeg;
}

Extinction extinction_from(const SectionOptics& s, const glm::dvec3& feature) {
  Extinction e;
  e.to_slow_deg = line_angle_deg(s.normal, feature, s.slow);
  const double to_slow = std::abs(e.to_slow_deg);
  e.nearer_is_slow = to_slow < 45.0;
  e.angle_deg = e.nearer_is_slow ? to_slow : 90.0 - to_slow;
  return e;
}

SignOfElongation sign_of_elongation(const SectionOptics& s, const glm::dvec3& elongation) {
  if (s.circular) return SignOfElongation::Indeterminate;
  const double to_slow = std::abs(line_angle_deg(s.normal, elongation, s.slow));
  if (std::abs(to_slow - 45.0) < 1e-9 * kDeg) return SignOfElongation::Indeterminate;
  return to_slow < 45.0 ? SignOfElongation::LengthSlow : SignOfElongation::LengthFast;
}

double retardation_nm(const SectionOptics& s, double thickness_um) {
  return thickness_um * 1000.0 * (s.n_slow - s.n_fast);
}

}  // namespace pmsim
