#pragma once
// The orientation conventions of EBSD files, written once: how a point's Bunge angles, read in the
// vendor's specimen and crystal frames, become pmsim's crystal-to-section rotation, and where a
// map point lies on the section. docs/ebsd.md draws the frames.
//
// Bunge angles: core/crystal/euler_angles.h (g = Z(φ2)·X(Φ)·Z(φ1), specimen → crystal).
//
// Crystal frames. pmsim: e1 ∥ a, e3 ∥ c* (core/crystal/lattice.h). The vendors:
//   Oxford Channel 5: x ∥ a*, z ∥ c for every crystal system ("x||a*, z||c", MTEX
//     interfaces/loadEBSD_ctf.m; for hexagonal phases x ∥ [10-10], y ∥ [-12-10], the DREAM3D
//     ReadCtfData documentation after Rollett's EBSD lecture notes, CMU 27-750). For hexagonal and
//     trigonal phases this is pmsim's frame turned +30° about c.
//   EDAX/TSL OIM: hexagonal and trigonal x ∥ a = [2-1-10], y ∥ [01-10] (DREAM3D ReadCtfData
//     documentation, same source; MTEX loadEBSD_ang's 'X||a' for Symmetry 3, 32, 6, 62);
//     monoclinic x ∥ a*, y ∥ b, z ∥ c (MTEX loadEBSD_ang: 'X||a*' for Symmetry 2, 'y||b, z||c'
//     for 20); triclinic x ∥ a, z ∥ c* (MTEX's 'X||a' for Symmetry 1; z ⟂ x then means c*).
//     OIM lets the hexagonal convention be chosen at installation (DREAM3D's caution); x ∥ a is
//     its default.
//   For cubic, tetragonal and orthorhombic cells all of these are the same axes.
//
// Specimen (Euler reference) frames, against the map as the vendor's software draws it (x right,
// y down, seen from the polished side, which faces the electron beam as it faces pmsim's
// observer):
//   Oxford Channel 5: x right, y up, z out of the polished surface — the map frame turned 180°
//     about x (MTEX loadEBSD_ctf: rotation.byAxisAngle(xvector, 180°) brings the two together).
//   EDAX/TSL OIM: x down (along the map's y), y right (along the map's x), z out of the surface —
//     the map frame turned 180° about x + y (MTEX loadEBSD_ang "setting 1", the one it assumes;
//     Britton et al., "Tutorial: Crystal orientations and EBSD — Or which way is up?", Materials
//     Characterization 117 (2016) 113–126). OIM can be set up otherwise (MTEX's settings 2–4);
//     such files need their angles rotated before use.
// pmsim's section frame is x east (the map's x), y north (against the map's y), z toward the
// observer (docs/conventions.md), so the Oxford Euler frame is pmsim's section frame itself.
#include <cstddef>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>

#include "core/crystal/euler_angles.h"
#include "core/crystal/lattice.h"
#include "core/ebsd/orientation_map.h"

namespace pmsim {

// Columns: the vendor's Cartesian crystal axes x, y, z written in pmsim's crystal frame, for a
// phase of `system` with `cell` (a proper rotation; the identity for cubic, tetragonal and
// orthorhombic cells). A vector with vendor components v has pmsim components R·v.
glm::dmat3 vendor_crystal_frame(EbsdVendor vendor, CrystalSystem system, const UnitCell& cell);

// Columns: the vendor's specimen (Euler reference) axes x, y, z written in pmsim's section frame.
glm::dmat3 vendor_specimen_frame(EbsdVendor vendor);

// pmsim's crystal-to-section rotation (columns: pmsim's crystal axes e1, e2, e3 in the section
// frame) of a point with Bunge angles `e` as the vendor wrote them:
//   S · crystal_to_sample_from_bunge(e) · Rᵀ,  S = vendor_specimen_frame, R = vendor_crystal_frame.
glm::dmat3 crystal_to_section(EbsdVendor vendor, const glm::dmat3& vendor_crystal_frame_R, const EulerBunge& e);

// Where point i lies on pmsim's section, in mm: the origin at the centre of the map's extent, x
// along the map's x, y against the map's y (the first row at the top: north).
glm::dvec2 section_position_mm(const OrientationMap& m, std::size_t i);

}  // namespace pmsim
