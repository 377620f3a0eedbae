#include "core/crystal/optical_orientation.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "core/base/json_reader.h"
#include "core/base/units.h"

namespace pmsim {

namespace {

int index_of(IndicatrixAxis a) { return static_cast<int>(a); }

// Columns in X, Y, Z order from the three axes placed, made right-handed by the sign of the last
// (an indicatrix axis is a line, not an arrow: its sign carries no information).
glm::dmat3 frame(const glm::dvec3 (&v)[3]) {
  glm::dmat3 m(v[0], v[1], v[2]);
  if (glm::dot(glm::cross(m[0], m[1]), m[2]) < 0) m[2] = -m[2];
  return m;
}

// The frame from two placed axes: `first` along the unit vector u, `second` along the unit vector
// v ⟂ u; the remaining axis is u × v, then the frame is made right-handed. The monoclinic and the
// triclinic orientations both give one axis fixed by symmetry or a plane normal and one in the
// plane ⟂ it.
glm::dmat3 frame_from_two_axes(IndicatrixAxis first, const glm::dvec3& u, IndicatrixAxis second,
                               const glm::dvec3& v) {
  glm::dvec3 axes[3];
  axes[index_of(first)] = u;
  axes[index_of(second)] = v;
  axes[3 - index_of(first) - index_of(second)] = glm::normalize(glm::cross(u, v));
  return frame(axes);
}

}  // namespace

char indicatrix_axis_name(IndicatrixAxis a) { return "XYZ"[index_of(a)]; }

glm::dmat3 indicatrix_axes(CrystalSystem system, const UnitCell& cell, const OpticalOrientation& o) {
  const bool uniaxial_system = system == CrystalSystem::Tetragonal || system == CrystalSystem::Hexagonal ||
                               system == CrystalSystem::Trigonal;
  const glm::dmat3 d = direct_basis(cell);
  const glm::dvec3 a = glm::normalize(d[0]), b = glm::normalize(d[1]), c = glm::normalize(d[2]);
  switch (o.kind) {
    case OpticalOrientation::Kind::Uniaxial: {
      if (!uniaxial_system)
        throw BadValue{std::string("a uniaxial orientation (optic axis ∥ c) needs a tetragonal, hexagonal or "
                                   "trigonal crystal, not ") +
                       crystal_system_name(system)};
      const glm::dvec3 x = glm::normalize(glm::cross(b, c));  // ⟂ c, in the a direction's half
      return glm::dmat3(x, glm::cross(c, x), c);
    }
    case OpticalOrientation::Kind::Orthorhombic: {
      if (system != CrystalSystem::Orthorhombic)
        throw BadValue{
            std::string("\"a\"/\"b\"/\"c\" → X/Y/Z assignments are for orthorhombic crystals, not ") +
            crystal_system_name(system)};
      const int ia = index_of(o.along_a), ib = index_of(o.along_b), ic = index_of(o.along_c);
      if (ia == ib || ib == ic || ia == ic) throw BadValue{"a, b and c must take X, Y and Z once each"};
      glm::dvec3 v[3];
      v[ia] = a, v[ib] = b, v[ic] = c;
      return frame(v);
    }
    case OpticalOrientation::Kind::Monoclinic: {
      if (system != CrystalSystem::Monoclinic)
        throw BadValue{std::string("a monoclinic orientation (axis ∥ b, angle in the a–c plane) needs a "
                                   "monoclinic crystal, not ") +
                       crystal_system_name(system)};
      if (o.inclined == o.along_b) throw BadValue{"the inclined axis cannot also be the one ∥ b"};
      if (!(std::isfinite(o.angle_deg) && o.angle_deg >= 0 && o.angle_deg <= 90))
        throw BadValue{"the angle to the crystal axis must be in [0, 90]°"};
      // In the a–c plane (⟂ b), rotating +c toward +a sweeps the obtuse angle β between them
      // (β > 90° in the standard setting); the acute side is the other way. Likewise from +a.
      const glm::dvec3 ref = o.from_a ? a : c, other = o.from_a ? c : a;
      const glm::dvec3 toward = glm::normalize(other - glm::dot(other, ref) * ref);  // ⟂ ref, +other side
      const double t = radians(o.angle_deg);
      const double s = o.side == MonoclinicSide::ObtuseBeta ? 1.0 : -1.0;
      const glm::dvec3 inclined = std::cos(t) * ref + s * std::sin(t) * toward;
      return frame_from_two_axes(o.along_b, b, o.inclined, inclined);
    }
    case OpticalOrientation::Kind::Triclinic: {
      if (system != CrystalSystem::Triclinic)
        throw BadValue{std::string("a plane-normal orientation is for triclinic crystals, not ") +
                       crystal_system_name(system)};
      if (o.inclined == o.normal_axis) throw BadValue{"the axis in the plane cannot also be its normal"};
      if (!(std::isfinite(o.angle_deg) && o.angle_deg > -90 && o.angle_deg <= 90))
        throw BadValue{"the angle in the plane must be in (-90, 90]°"};
      const glm::dvec3 n = plane_normal(cell, o.normal_plane);
      const glm::dvec3 r = lattice_direction(cell, o.reference_direction);
      const glm::dvec3 rp = r - glm::dot(r, n) * n;
      if (glm::length(rp) < 1e-6) throw BadValue{"the reference direction is normal to the plane: it has no trace in it"};
      const glm::dvec3 u = glm::normalize(rp), w = glm::cross(n, u);  // u, w span the plane, n × u = w
      const double t = radians(o.angle_deg);
      const glm::dvec3 inclined = std::cos(t) * u + std::sin(t) * w;  // rotation by t about +n
      return frame_from_two_axes(o.normal_axis, n, o.inclined, inclined);
    }
  }
  throw BadValue{"unknown optical orientation"};
}

}  // namespace pmsim
