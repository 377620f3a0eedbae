#pragma once
// What a mineral file says about the crystal as a lattice: its system and unit cell, where the
// indicatrix lies in it, its cleavages, habit and twin laws. Optional per mineral; every block
// cites its source. Derived quantities (cleavage angles, extinction angles, signs of elongation)
// are computed from these (core/crystal/section_optics.h), never typed in.
//
// Mineral-file keys (all optional together; crystal_system and unit_cell required by the others):
//   "crystal_system": "cubic|tetragonal|hexagonal|trigonal|orthorhombic|monoclinic|triclinic",
//   "unit_cell": {"a": Å, "b": Å, "c": Å, "alpha": °, "beta": °, "gamma": °, "source": "..."},
//   "optical_orientation": one of
//       {"optic_axis": "c", "source"}                                  (uniaxial)
//       {"a": "X|Y|Z", "b": …, "c": …, "source"}                        (orthorhombic)
//       {"b": "X|Y|Z", "inclined": {"axis": "X|Y|Z", "from": "c|a", "angle_deg": θ,
//        "side": "obtuse_beta|acute_beta"}, "source"}                   (monoclinic, b unique)
//       {"normal_to": "(100)", "axis": "X", "in_plane": {"axis": "Z", "from": "[001]",
//        "angle_deg": θ}, "source"}                                     (triclinic)
//   "cleavage": [{"plane": "(110)", "quality": "perfect|very_good|good|distinct|fair|imperfect|
//                 poor|parting", "source"}, …]  — each symmetry-equivalent plane that shows in thin
//                 section listed on its own ((110) and (1-10)),
//   "habit": {"elongation": "[001]", "tabular": "(001)", "source"} (either or both),
//   "twins": [{"law": "albite", "plane": "(010)", "source"}, …].
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>

#include "core/crystal/crystal.h"
#include "core/crystal/lattice.h"
#include "core/crystal/optical_orientation.h"

namespace pmsim {

class JsonReader;

enum class CleavageQuality { Perfect, VeryGood, Good, Distinct, Fair, Imperfect, Poor, Parting };

struct Cleavage {
  MillerIndices plane;
  CleavageQuality quality = CleavageQuality::Good;
  std::string source;
};

struct Habit {
  std::optional<LatticeDirection> elongation;  // prismatic/acicular along this direction
  std::optional<MillerIndices> tabular;        // platy ∥ this plane
  std::string source;
};

struct TwinLaw {
  std::string law;  // "albite", "carlsbad", …
  MillerIndices plane;
  std::string source;
};

struct MineralCrystallography {
  CrystalSystem system = CrystalSystem::Triclinic;
  UnitCell cell;
  std::string cell_source;
  std::optional<OpticalOrientation> orientation;
  // Columns X, Y, Z of the indicatrix in the crystal Cartesian frame (lattice.h); computed from
  // `orientation` at load; meaningful only when it is set.
  glm::dmat3 indicatrix_axes{1.0};
  std::vector<Cleavage> cleavage;
  Habit habit;
  std::vector<TwinLaw> twins;
};

// Reads the keys above from a mineral file's root object; nullopt when it has none of them.
// `symmetry` is the file's optical symmetry: a uniaxial crystal takes the uniaxial orientation,
// a biaxial one an orthorhombic, monoclinic or triclinic one; an isotropic one none (its cell
// and cleavage are still read: garnet, halite). Throws InputError naming file, key and value.
std::optional<MineralCrystallography> read_mineral_crystallography(const JsonReader& root,
                                                                   CrystalSymmetry symmetry);

// The library's data for a mineral (any name find_mineral takes: aliases, compositions, which
// share their series' file data); nullptr when its file has none. The pointer stays valid for the
// process. Throws InputError for an unknown mineral, as find_mineral does.
const MineralCrystallography* find_mineral_crystallography(std::string_view name);

// Whether a grain of crystal `c` placed by a crystal frame (a section grain's euler_deg, an EBSD
// orientation) has only a stand-in for its indicatrix there: `c` is anisotropic and its mineral
// data `m` (nullptr: none) has no optical_orientation, so X, Y, Z are taken along the crystal
// frame's e1, e2, e3 (section_map.cpp indicatrix_in_section) and its extinction angles are not
// the mineral's (issue 22; plagioclase today, decided by its file, not its name).
// An isotropic crystal needs no orientation: false.
bool optical_orientation_is_stand_in(const MineralCrystallography* m, const Crystal& c);

// load_mineral_file (crystal.h) that also returns the file's crystallography.
Crystal load_mineral_file(const std::string& path, std::optional<MineralCrystallography>* crystallography);

}  // namespace pmsim
