#pragma once
// The crystal lattice: a unit cell, its crystal system, and the Cartesian crystal frame in which
// plane normals (hkl) and lattice directions [uvw] become vectors.
//
// Crystal Cartesian frame (the convention of the PDB/International Tables "standard orthogonal
// frame", also used by EBSD software with Bunge angles): e1 ∥ a, e3 ∥ c* (the normal of (001)),
// e2 = e3 × e1. So a = a·(1, 0, 0); b = b·(cos γ, sin γ, 0); c has c·cos β along e1. For a
// monoclinic cell with b unique (α = γ = 90°) e2 ∥ b and c lies in the e1–e3 plane, tilted by
// β − 90° from e3 toward −e1 (Giacovazzo et al., "Fundamentals of Crystallography", 3rd ed. 2011;
// International Tables for Crystallography vol. B §1.1).
#include <array>
#include <string>
#include <string_view>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace pmsim {

enum class CrystalSystem { Cubic, Tetragonal, Hexagonal, Trigonal, Orthorhombic, Monoclinic, Triclinic };

// "cubic", "tetragonal", … as spelled in mineral files.
const char* crystal_system_name(CrystalSystem s);

struct UnitCell {
  double a_A = 1, b_A = 1, c_A = 1;                      // edge lengths, ångström
  double alpha_deg = 90, beta_deg = 90, gamma_deg = 90;  // α = b∧c, β = c∧a, γ = a∧b
};

// The constraints of each system on the cell (Giacovazzo 2011), with hexagonal and
// trigonal in the hexagonal setting (a = b, α = β = 90°, γ = 120°; rhombohedral cells are given in
// that setting too) and monoclinic with b unique (α = γ = 90°, β ≠ 90°). Edges must be > 0, angles
// in (0°, 180°) with a real cell volume. Throws BadValue (core/base/json_reader.h) naming the rule.
// Equalities hold to 1e-9 relative (the values are typed from tables, not computed).
void check_unit_cell(CrystalSystem system, const UnitCell& cell);

// Columns a, b, c of the direct lattice in the crystal Cartesian frame (Å).
glm::dmat3 direct_basis(const UnitCell& cell);
// Columns a*, b*, c* (Å⁻¹): a* = (b × c)/V, …, so that a_i · a*_j = δ_ij.
glm::dmat3 reciprocal_basis(const UnitCell& cell);

struct MillerIndices {  // a plane (hkl)
  int h = 0, k = 0, l = 1;
};
struct LatticeDirection {  // a direction [uvw]
  int u = 0, v = 0, w = 1;
};

// Unit normal of (hkl): h a* + k b* + l c*, normalised.
glm::dvec3 plane_normal(const UnitCell& cell, MillerIndices p);
// Unit vector along [uvw]: u a + v b + w c, normalised.
glm::dvec3 lattice_direction(const UnitCell& cell, LatticeDirection d);

// Text forms: "(hkl)" and "[uvw]" with single-digit indices written together, a minus sign before
// a negative one ("(1-10)", "[-101]"), or indices separated by spaces or commas for several digits
// ("(1 -1 0)", "[1,0,12]"). The four-index Miller–Bravais forms of hexagonal and trigonal crystals
// are accepted too: "(10-14)" is (hkil) with i = −(h + k) required, read as (h k l); "[2-1-10]" is
// [UVTW] with T = −(U + V) required, read as [u v w] = [U − T, V − T, W] = [2U + V, U + 2V, W]
// (Frank 1965, Acta Cryst. 18, 862; "[2-1-10]" is [300], i.e. along a). All-zero indices are refused.
// Throw BadValue with the reason; the caller names the key.
MillerIndices parse_miller_plane(std::string_view text);
LatticeDirection parse_lattice_direction(std::string_view text);
std::string miller_text(MillerIndices p);        // "(1-10)"
std::string direction_text(LatticeDirection d);  // "[-101]"

}  // namespace pmsim
