#pragma once
// Where the indicatrix axes X (nα), Y (nβ), Z (nγ) lie in the crystal, from the data as optical
// mineralogy tables publish them (Nesse 2012 ch. 7 and the mineral descriptions; Deer, Howie &
// Zussman 2013, who write α, β, γ for X, Y, Z and x, y, z for the crystal axes a, b, c):
//   uniaxial (tetragonal, hexagonal, trigonal): the optic axis (Z of pmsim's uniaxial crystals,
//     the nε direction) ∥ c;
//   orthorhombic: which of X, Y, Z lies along a, b and c ("X = b, Y = c, Z = a" for forsterite);
//   monoclinic, b unique: which of X, Y, Z is ∥ b, and the angle of one of the two others from c
//     (or from a) in the a–c plane, with the side it lies on: in the obtuse angle β (rotated from
//     +c toward +a, or from +a toward +c) or in the acute one (from +c away from +a, i.e. toward
//     −a; from +a away from +c). "Z ∧ c = 44°, in the obtuse angle β" is augite.
//   triclinic: as the tables give it for kyanite ("X ⟂ (100); Z′ ∧ c = 27–32° on (100)"): one
//     indicatrix axis along the normal of a plane (hkl), a second one in that plane at an angle
//     from the trace of a lattice direction [uvw] projected into it, counter-clockwise seen from
//     the +normal side (right-handed about the normal); the third completes the frame.
// Plagioclase has no orientation: its published data (Burri, Parker & Wenk 1967) are the
// spherical coordinates of X, Y, Z for each composition, not tabulated here yet.
#include <optional>
#include <string>

#include <glm/mat3x3.hpp>

#include "core/crystal/lattice.h"

namespace pmsim {

enum class IndicatrixAxis { X, Y, Z };
enum class MonoclinicSide { ObtuseBeta, AcuteBeta };

struct OpticalOrientation {
  enum class Kind { Uniaxial, Orthorhombic, Monoclinic, Triclinic };
  Kind kind = Kind::Uniaxial;
  // Orthorhombic: the indicatrix axis along a, b, c (a permutation of X, Y, Z).
  IndicatrixAxis along_a = IndicatrixAxis::X, along_b = IndicatrixAxis::Y, along_c = IndicatrixAxis::Z;
  // Monoclinic: along_b as above; `inclined` (≠ along_b) at angle_deg from reference axis c (or a
  // when from_a) on `side`; the third axis completes the frame.
  IndicatrixAxis inclined = IndicatrixAxis::Z;
  bool from_a = false;
  double angle_deg = 0.0;
  MonoclinicSide side = MonoclinicSide::ObtuseBeta;
  // Triclinic: `normal_axis` ∥ the normal of `normal_plane`; `inclined` (≠ normal_axis) in that
  // plane at angle_deg (signed, (−90°, 90°]) from the projection of `reference_direction`.
  IndicatrixAxis normal_axis = IndicatrixAxis::X;
  MillerIndices normal_plane{1, 0, 0};
  LatticeDirection reference_direction{0, 0, 1};
  std::string source;  // citation
};

// Columns: X, Y, Z (unit vectors) in the crystal Cartesian frame of lattice.h, right-handed.
// For uniaxial crystals Z = c and X, Y complete a right-handed frame (X ∥ a*, ⟂ b and c; any
// choice is equivalent since nX = nY). Throws BadValue when the data do not fit the system (e.g. a monoclinic
// orientation for an orthorhombic cell, the inclined axis equal to the one ∥ b, a repeated axis).
glm::dmat3 indicatrix_axes(CrystalSystem system, const UnitCell& cell, const OpticalOrientation& o);

char indicatrix_axis_name(IndicatrixAxis a);  // 'X', 'Y', 'Z'

}  // namespace pmsim
