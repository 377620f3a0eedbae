#include "core/crystal/crystal_cut.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/base/json_reader.h"
#include "core/base/units.h"

namespace pmsim {

double direction_plane_angle_deg(const UnitCell& cell, MillerIndices plane, LatticeDirection north) {
  const glm::dvec3 n = plane_normal(cell, plane), d = lattice_direction(cell, north);
  // atan2 of sine and cosine: accurate near 0° and 90° alike (asin loses half the digits at 90°).
  return degrees(std::atan2(std::abs(glm::dot(n, d)), glm::length(glm::cross(n, d))));
}

glm::dmat3 crystal_to_lab_of_cut(const UnitCell& cell, MillerIndices plane, LatticeDirection north) {
  const glm::dvec3 n = plane_normal(cell, plane);
  glm::dvec3 d = lattice_direction(cell, north);
  if (std::abs(glm::dot(n, d)) > 1e-6)
    throw BadValue{"direction " + direction_text(north) + " makes " +
                   number_text(direction_plane_angle_deg(cell, plane, north)) + "° with the plane " +
                   miller_text(plane) + "; north must lie in the section plane (to 1e-6)"};
  d = glm::normalize(d - glm::dot(d, n) * n);  // in the plane to rounding
  const glm::dvec3 e = glm::cross(d, n);       // east: x = y × z
  // Rows are the crystal vectors that become lab x, y, z: the rotation R with R·e = x, R·d = y,
  // R·n = z is the transpose of the matrix with columns e, d, n.
  return glm::transpose(glm::dmat3(e, d, n));
}

glm::dmat3 cut_orientation(const MineralCrystallography& m, MillerIndices plane, LatticeDirection north) {
  if (!m.orientation) throw BadValue{"the mineral file gives no optical_orientation"};
  return crystal_to_lab_of_cut(m.cell, plane, north) * m.indicatrix_axes;
}

glm::dmat3 cut_plate_orientation(const Crystal& c, std::string_view plane, std::string_view north) {
  const MineralCrystallography* m = find_mineral_crystallography(c.name());
  if (!m || !m->orientation)
    throw BadValue{"mineral '" + c.name() + "' has no unit cell and optical orientation data for a cut"};
  const glm::dmat3 o = cut_orientation(*m, parse_miller_plane(plane), parse_lattice_direction(north));
  if (c.symmetry() == CrystalSymmetry::Biaxial) return biaxial_orientation(o[0], o[2]);
  return uniaxial_orientation(o[2]);
}

}  // namespace pmsim
