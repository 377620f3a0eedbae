#pragma once
// What a student can observe of a library mineral in thin section, computed from its file (indices,
// absorption, crystallography) — the columns of a determinative table (Nesse 2012, appendix
// tables), never typed in. pmsim-exercise identify matches a student's observations against these.
#include <array>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace pmsim {

// Relief against a mounting medium of n = 1.54 (Canada balsam, epoxy; Nesse 2012 ch. 4), by how far
// the index lies from it. Nesse names the classes without bounds; pmsim's bounds: |n − 1.54| below
// 0.04 low, below 0.12 moderate, below 0.22 high, beyond very high. A mineral whose indices span
// two classes (calcite) shows both, as its relief changes on turning the stage.
enum class ReliefClass { Low, Moderate, High, VeryHigh };
const char* relief_class_name(ReliefClass r);  // "low", "moderate", "high", "very_high"
ReliefClass relief_class(double n);
constexpr double kReliefMediumIndex = 1.54;

struct MineralSignature {
  std::string mineral;
  std::string character;  // "isotropic", "uniaxial", "biaxial"
  std::string optic_sign;  // "", "positive", "negative"
  double two_v_deg = 0.0;  // about the acute bisectrix; 0 uniaxial
  double n_min = 0.0, n_max = 0.0, birefringence = 0.0;  // at 589.3 nm
  std::set<ReliefClass> relief;
  std::vector<std::string> relief_signs;  // "positive" (n > 1.54) and/or "negative"
  // Colour in plane light through 30 µm for light vibrating along X, Y, Z (CIELAB under D65), and
  // what an observer calls it: coloured when any axis lies more than 5 ΔE*ab from white,
  // pleochroic when two axes differ by more than 5 (a clearly visible difference; the just-
  // noticeable one is ≈ 2.3, Sharma 2003, Digital Color Imaging Handbook ch. 1).
  bool coloured = false, pleochroic = false;
  double colour_delta_e = 0.0, pleochroism_delta_e = 0.0;
  std::size_t cleavages = 0;  // cleavage planes listed (each symmetry-equivalent plane on its own)
  std::vector<std::string> twin_laws;
  // Extinction over the sections that show the feature (a zone of the elongation, the sections
  // across a tabular habit, or across the first cleavage): the range of the angle to it, which
  // types occur, and the signs of elongation. Unset without crystallography or a feature.
  std::optional<double> extinction_min_deg, extinction_max_deg;
  std::set<std::string> extinction_types;  // "parallel", "inclined", "symmetric"
  std::set<std::string> elongation_signs;  // "length-slow", "length-fast"
  std::string feature;                     // what the extinction is measured to, in words
  // Opaque in 30 µm (core/crystal/opacity.h: magnetite, ilmenite): black in plane and crossed
  // light, so a student sees none of relief, colour, interference colour, character or
  // extinction; the fields above still hold the file's values (a reference), not observations.
  bool opaque = false;
};

MineralSignature mineral_signature(const std::string& mineral);
// The same, computed once per name for the process (thread-safe; the reference stays valid).
const MineralSignature& cached_mineral_signature(const std::string& mineral);

// CIELAB (D65 white, Y = 100) of white light through `thickness_um` of the mineral vibrating along
// its X, Y and Z axes (Beer–Lambert on the file's absorption; white for a non-absorbing one): the
// colours of its pleochroism in plane light.
std::array<glm::dvec3, 3> principal_colours_lab(const std::string& mineral, double thickness_um = 30.0);
// Every library mineral's signature (computed once).
const std::vector<MineralSignature>& library_signatures();

// Highest interference order of a mineral at a thickness: ⌈thickness × δ / 550 nm⌉ (orders end
// at multiples of 550 nm on the Michel-Lévy chart, Nesse 2012 §7.5); 0 for an isotropic one.
int max_interference_order(double birefringence, double thickness_um);

}  // namespace pmsim
