#pragma once
// Bunge Euler angles (φ1, Φ, φ2): the orientation of a crystal in a specimen as the rotation g that
// takes specimen coordinates to crystal coordinates, g = Z(φ2)·X(Φ)·Z(φ1) — rotate about the
// specimen z by φ1, about the new x by Φ, about the new z by φ2 (Bunge 1982, "Texture Analysis in
// Materials Science", eq. 2.38; the convention of EBSD software). The rows of g are the crystal
// Cartesian axes (core/crystal/lattice.h: e1 ∥ a, e3 ∥ c*) written in the specimen frame, so
// crystal_to_sample = gᵀ. The specimen frame here is the section frame of docs/conventions.md
// (x east, y north, z toward the observer, at stage 0°).
#include <glm/mat3x3.hpp>

namespace pmsim {

struct EulerBunge {
  double phi1_rad = 0.0, Phi_rad = 0.0, phi2_rad = 0.0;
};

// Columns: the crystal frame's e1, e2, e3 in the specimen frame (gᵀ).
glm::dmat3 crystal_to_sample_from_bunge(const EulerBunge& e);

// The inverse, for a proper rotation (det +1; columns orthonormal to 1e-6, else
// std::invalid_argument). φ1, φ2 in [0, 2π), Φ in [0, π]. At Φ = 0 or π only φ1 ± φ2 is defined:
// φ2 = 0 is returned then.
EulerBunge bunge_from_crystal_to_sample(const glm::dmat3& crystal_to_sample);

}  // namespace pmsim
