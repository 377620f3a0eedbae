#pragma once
// A plate cut along a crystal plane: the section plane (hkl) lies in the stage, and a lattice
// direction [uvw] in it points north (lab +y) at stage 0°. Lab frame: x east, y north, z toward
// the observer; the plane's normal h a* + k b* + l c* points toward the observer.
#include <string_view>

#include <glm/mat3x3.hpp>

#include "core/crystal/lattice.h"
#include "core/crystal/mineral_crystallography.h"

namespace pmsim {

// Angle (°) between [uvw] and the plane (hkl): 0 when the direction lies in it (the zone law
// hu + kv + lw = 0 for integer indices; computed here as an angle so the message can say how far
// off a wrong choice is).
double direction_plane_angle_deg(const UnitCell& cell, MillerIndices plane, LatticeDirection north);

// The rotation of the cut, crystal Cartesian vectors (lattice.h) → lab vectors at stage 0°: plane
// normal → +z, north → +y, north × normal → +x. Throws BadValue as cut_orientation does.
glm::dmat3 crystal_to_lab_of_cut(const UnitCell& cell, MillerIndices plane, LatticeDirection north);

// The indicatrix of the cut in the lab frame at stage 0°: columns X, Y, Z (nα, nβ, nγ; uniaxial:
// Z the optic axis), the form sample.x_axis/z_axis/optic_axis describe. Throws BadValue when the
// mineral has no optical orientation, or when north does not lie in the plane: |n̂·d̂| > 1e-6
// (unit vectors; the zone law holds exactly for a true zone, so 1e-6 only absorbs rounding), the
// message giving the angle.
glm::dmat3 cut_orientation(const MineralCrystallography& m, MillerIndices plane, LatticeDirection north);

// The crystal-to-lab matrix a plate of library mineral `c` cut along `plane` ("(hkl)") with
// `north` ("[uvw]") renders with: cut_orientation turned into the renderer's form by the same
// uniaxial_orientation / biaxial_orientation (crystal.h) that typed sample axes go through, so a
// cut and the axes it amounts to give the same plate. Throws BadValue for malformed text, a
// mineral without crystallographic data and north out of the plane.
glm::dmat3 cut_plate_orientation(const Crystal& c, std::string_view plane, std::string_view north);

}  // namespace pmsim
