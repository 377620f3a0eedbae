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
// Triclinic minerals (plagioclase) carry no orientation yet: their published data are angles to
// poles of several faces (or Euler angles on a universal stage) and vary with composition.
#include <optional>
#include <string>

#include <glm/mat3x3.hpp>

#include "core/crystal/lattice.h"

namespace pmsim {

enum class IndicatrixAxis { X, Y, Z };
enum class MonoclinicSide { ObtuseBeta, AcuteBeta };

struct OpticalOrientation {
  enum class Kind { Uniaxial, Orthorhombic, Monoclinic };
  Kind kind = Kind::Uniaxial;
  // Orthorhombic: the indicatrix axis along a, b, c (a permutation of X, Y, Z).
  IndicatrixAxis along_a = IndicatrixAxis::X, along_b = IndicatrixAxis::Y, along_c = IndicatrixAxis::Z;
  // Monoclinic: along_b as above; `inclined` (≠ along_b) at angle_deg from reference axis c (or a
  // when from_a) on `side`; the third axis completes the frame.
  IndicatrixAxis inclined = IndicatrixAxis::Z;
  bool from_a = false;
  double angle_deg = 0.0;
  MonoclinicSide side = MonoclinicSide::ObtuseBeta;
  std::string source;  // citation
};

// Columns: X, Y, Z (unit vectors) in the crystal Cartesian frame of lattice.h, right-handed.
// For uniaxial crystals Z = c and X, Y complete a right-handed frame (X ∥ a*, ⟂ b and c; any
// choice is equivalent since nX = nY). Throws BadValue when the data do not fit the system (e.g. a monoclinic
// orientation for an orthorhombic cell, the inclined axis equal to the one ∥ b, a repeated axis).
glm::dmat3 indicatrix_axes(CrystalSystem system, const UnitCell& cell, const OpticalOrientation& o);

char indicatrix_axis_name(IndicatrixAxis a);  // 'X', 'Y', 'Z'

}  // namespace pmsim
