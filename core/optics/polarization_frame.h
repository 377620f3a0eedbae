#pragma once
// The polarization frame at a hit (docs/conventions.md, one frame for the whole project):
//   s   = unit(d × N)      perpendicular to the plane of incidence (E⊥)
//   p_i = d × s            in the plane of incidence, incident ray   (s × p_i =  d)
//   p_t = t × s            refracted ray                             (s × p_t =  t)
//   p_r = s × r            reflected ray                             (p_r × s =  r)
// N is the surface normal, either orientation: flipping N flips s and every p together, which
// leaves each field component s·(E·s) unchanged. In this frame fresnel.h's amplitudes (and the
// paper's flip rules, normal-incidence ratio and TIR phases) give the physical field.
// At normal incidence d × N vanishes and every s ⟂ d gives the same physical result (r_s = r_p,
// t_s = t_p); we then pick s from the coordinate axis least aligned with d, which never fails.
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace pmsim {

// A unit vector perpendicular to unit vector d, continuous over large regions of directions
// (Frisvad-style choice of the helper axis by the smallest component).
inline glm::dvec3 any_perpendicular(const glm::dvec3& d) {
  const glm::dvec3 a = glm::abs(d);
  const glm::dvec3 helper = (a.x <= a.y && a.x <= a.z) ? glm::dvec3(1, 0, 0)
                            : (a.y <= a.z)             ? glm::dvec3(0, 1, 0)
                                                       : glm::dvec3(0, 0, 1);
  return glm::normalize(glm::cross(d, helper));
}

// s = unit(d × N); below this |d × N| the incidence is treated as normal (there r_s − r_p is
// O(sin²θ) ≈ 1e-24, so the switch is invisible; the direction error of the cross product itself
// is corrected in polarization_frame).
inline glm::dvec3 perpendicular_axis(const glm::dvec3& d, const glm::dvec3& N) {
  const glm::dvec3 c = glm::cross(d, N);
  const double len2 = glm::dot(c, c);
  if (len2 > 1e-24) return c / std::sqrt(len2);
  return any_perpendicular(d);
}

struct PolarizationFrame {
  glm::dvec3 s;    // ⟂ plane of incidence
  glm::dvec3 p_i;  // d × s
};

inline PolarizationFrame polarization_frame(const glm::dvec3& d, const glm::dvec3& N) {
  // Near normal incidence the normalized cross product carries a direction error of about
  // 1e-16/|d × N| (1e-7 at |d × N| = 1e-9), enough to tilt s out of the plane ⟂ d and, after a
  // few internal reflections, leave v_p measurably not ⟂ dir (fuzz input
  // tests/fuzz/regressions/trace_lens/pol_not_perpendicular_near_normal.bin). Projecting s back
  // onto the plane ⟂ d removes that: then s·d, s·r and s·t are all at rounding level, because r
  // and t lie in span(d, N) and s·N = sinθ·(error) is second order.
  glm::dvec3 s = perpendicular_axis(d, N);
  s = glm::normalize(s - glm::dot(s, d) * d);
  return {s, glm::cross(d, s)};
}
inline glm::dvec3 p_refracted(const glm::dvec3& s, const glm::dvec3& t) { return glm::cross(t, s); }
inline glm::dvec3 p_reflected(const glm::dvec3& s, const glm::dvec3& r) { return glm::cross(s, r); }

}  // namespace pmsim
