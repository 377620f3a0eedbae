#pragma once
// What a section of a crystal shows at normal incidence, computed from the indicatrix: the two
// vibration directions (the principal axes of the central section of the indicatrix ellipsoid
// x²/nX² + y²/nY² + z²/nZ² = 1 normal to the wave normal; Nesse 2012 §7, Born & Wolf §15.3), their
// indices, the retardation, extinction angles and the sign of elongation.
//
// Definitions (Nesse 2012 ch. 7; Deer, Howie & Zussman 2013 appendix):
//   extinction angle: the angle between a linear feature of the section (a cleavage trace, the
//     trace of a crystal face, the elongation) and the nearer vibration direction, in [0°, 45°];
//     0 is parallel extinction. The "Z ∧ c" of monoclinic tables is the angle to the slow one.
//   sign of elongation: length-slow (positive) when the slow vibration direction (n′γ) is the
//     nearer one to the elongation, length-fast (negative) when the fast one (n′α) is; within
//     1e-9 rad of 45° (or in a circular section) it is indeterminate.
// All vectors here are unit vectors in one frame (the crystal Cartesian frame of lattice.h, or
// the lab frame: the functions do not care as long as all inputs share it).
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace pmsim {

struct SectionOptics {
  glm::dvec3 normal{0, 0, 1};  // the section's normal (the wave normal)
  glm::dvec3 fast{1, 0, 0};    // vibration direction of the lower index n′α
  glm::dvec3 slow{0, 1, 0};    // vibration direction of the higher index n′γ, slow = normal × fast
  double n_fast = 1.0, n_slow = 1.0;
  bool circular = false;  // n′α = n′γ (to 1e-12): a section ⟂ an optic axis, no directions
};

// indicatrix_axes: columns X, Y, Z; principal_indices: (nX, nY, nZ) at the wavelength of interest.
SectionOptics section_optics(const glm::dmat3& indicatrix_axes, const glm::dvec3& principal_indices,
                             const glm::dvec3& section_normal);

// The trace of a plane (its unit normal) on the section: normal × plane_normal, unit. Throws
// std::invalid_argument if the plane is the section itself (no trace).
glm::dvec3 plane_trace(const glm::dvec3& section_normal, const glm::dvec3& plane_normal);
// A direction projected into the section, unit (an elongation seen in the section). Throws
// std::invalid_argument for a direction along the normal.
glm::dvec3 projected_direction(const glm::dvec3& section_normal, const glm::dvec3& direction);

// Signed angle (°, in (−90, 90]) from line `from` to line `to` in the section, counter-clockwise
// as seen from the side the normal points to (the observer, for a cut: lab +z).
double line_angle_deg(const glm::dvec3& section_normal, const glm::dvec3& from, const glm::dvec3& to);
// The angle between two lines (traces), in [0°, 90°]: the acute angle (the obtuse one is 180° −).
double trace_angle_deg(const glm::dvec3& t1, const glm::dvec3& t2);

struct Extinction {
  double angle_deg = 0.0;  // to the nearer vibration direction, [0, 45]
  bool nearer_is_slow = false;
  double to_slow_deg = 0.0;  // signed line angle from the feature to the slow direction
};
Extinction extinction_from(const SectionOptics& s, const glm::dvec3& feature);

enum class SignOfElongation { LengthSlow, LengthFast, Indeterminate };
SignOfElongation sign_of_elongation(const SectionOptics& s, const glm::dvec3& elongation_in_section);

// Retardation Γ = d·(n′γ − n′α) in nm for a thickness d in µm (Nesse 2012 ch. 6, the relation
// the Michel-Lévy chart plots).
double retardation_nm(const SectionOptics& s, double thickness_um);

}  // namespace pmsim
