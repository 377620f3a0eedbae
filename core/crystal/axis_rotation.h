#pragma once
// Rotations about an axis, shared by the texture engine (a fabric turning a crystal toward its
// lineation) and the section map (subgrain walls turning a lattice by their step).
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace pmsim {

// Rotation by angle θ about unit axis u (Rodrigues): R = cos θ I + sin θ [u]× + (1 − cos θ) uuᵀ.
glm::dmat3 axis_rotation(const glm::dvec3& unit_axis, double angle_rad);

// The smallest rotation taking unit vector a to unit vector b: about a × b by the angle between
// them; the identity when they are parallel (|a × b| ≤ 1e-12; antiparallel vectors have no
// smallest rotation, and the callers take axes, not vectors, so they flip b first).
glm::dmat3 rotation_taking(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace pmsim
