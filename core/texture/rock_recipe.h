#pragma once
// A rock recipe (assets/rocks/*.json, format in docs/rocks.md): what the texture engine grows a
// thin section from. The modal composition, each phase's crystal-size distribution and habit, the
// order of crystallisation, zoning and twinning, and the sources of all of them.
//
//   {"type": "rock", "name": "andesite", "source": "...", "texture": "porphyritic, ...",
//    "seed": 1, "size_mm": [8, 6], "thickness_um": 30,
//    "matrix": {"mineral": "glass", "source": "..."},            (optional: glass fills the rest)
//    "phases": [{"name": "plagioclase phenocrysts", "mineral": "plagioclase:An55",
//                "mode_percent": 20,
//                "csd": {"slope_per_mm": -3.0, "min_mm": 0.3, "max_mm": 2.5, "source": "..."},
//                   or {"law": "log-normal", "median_mm": 0.35, "sorting_phi": 0.45, "min_mm", "max_mm"}
//                                            (a sorted sand; "law" is "log-linear" by default)
//                "nucleation": 0.0,          (when the phase begins, 0 … 1 of the cooling time)
//                "aspect": 3,                (optional; the mineral's default otherwise)
//                "shape": "habit|rounded",   (optional: "rounded" detrital grains are balls)
//                "porphyroblast": true,      (optional: grows over the matrix it meets)
//                "zoning": {"kind": "oscillatory|normal", "core": 60, "rim": 40,
//                           "amplitude": 6, "bands": 12},          (optional; composition numbers)
//                "twin": {"law": "albite", "lamella_mm": 0.03, "fraction": 0.8,   (optional)
//                         "cross": {"law": "pericline", "lamella_mm": 0.03}},  (optional: tartan)
//                "fabric": {"align": "elongation|plate_normal", "direction": [1, 0, 0],
//                           "spread_deg": 15},  (optional: a shape-preferred orientation)
//                "undulose": {"subgrain_mm": 0.05, "step_deg": 1.5},  (optional: bent, polygonized)
//                "alteration": {"mineral": "antigorite", "vein_mm": 0.02, "fraction": 1,
//                               "orientation": "random|host"},
//                                            (optional: the cracks filled with a secondary mineral)
//                "inclusions": {"mineral": "quartz", "size_mm": 0.04, "aspect": 2.5, "spacing_mm": 0.1,
//                               "trail_spacing_mm": 0.08, "fraction": 0.6, "within": 0.85,
//                               "trail_deg": 15, "rotation_deg": 90, "orientations": 4,
//                               "habit": "trail|needle|wedge", "halo": {"radius_mm", "darkening"}},
//                                            (optional: a poikiloblast's inclusion trails,
//                                             needles along their own c, haloes)
//                "overgrowth": {"cement_percent": 5, "dust": {"mineral": "aqueous_fluid", "size_mm": 0.004,
//                               "spacing_mm": 0.008, "fraction": 0.6}},
//                                            (optional, on a rounded phase in a rock with pores:
//                                             syntaxial cement with a dust line)
//                "myrmekite": {"host": "microcline", "depth_mm": 0.12, "bulb_mm": 0.25, "fraction": 0.5,
//                              "quartz": {"mineral": "quartz", "width_mm": 0.006, "spacing_mm": 0.018}},
//                                            (optional: bulbs of vermicular quartz into another
//                                             phase's grains; core/texture/myrmekite.h)
//                "source": "..."}, ...],
//  "granoblastic": {"grain_mm": 0.3, "relax_iterations": 12}}   (optional; phases then need no csd)
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/base/json_reader.h"

namespace pmsim {

struct CsdRecipe {
  enum class Law { log_linear, log_normal };
  // log_linear: population density n(L) = n0·exp(slope·L) between min_mm and max_mm, the CSD of
  // steady-state crystallisation (Marsh 1988, Contrib. Mineral. Petrol. 99, 277–291; Higgins
  // 2006, Quantitative Textural Measurements in Igneous and Metamorphic Petrology, ch. 5).
  // log_normal: a sorted sediment's grain diameters, normal in φ = −log₂(L / 1 mm) (Krumbein 1934,
  // J. Sediment. Petrol. 4, 65–77) with median φ₅₀ = −log₂(median_mm) and standard deviation
  // sorting_phi, Folk & Ward's (1957, J. Sediment. Petrol. 27, 3–26) sorting: under 0.35 very well
  // sorted, 0.35–0.50 well, 0.50–0.71 moderately well, 0.71–1.00 moderately sorted. The numbers
  // are of grains (what a thin section counts), not of sieve weights.
  Law law = Law::log_linear;
  double slope_per_mm = -5.0;                 // log_linear
  double median_mm = 0.25, sorting_phi = 0.5;  // log_normal
  double min_mm = 0.05, max_mm = 1.0;
  // n(L) up to a constant factor, per millimetre of size.
  double density(double size_mm) const;
};

struct ZoningRecipe {
  bool oscillatory = false;       // else normal: core → rim in equal steps
  double core = 0.0, rim = 0.0;   // composition numbers (An content of "plagioclase:An55")
  double amplitude = 0.0;         // oscillation about the normal trend (oscillatory)
  int bands = 1;
};

struct TwinRecipe {
  std::string law;
  double lamella_mm = 0.0;  // 0: simple twins
  double fraction = 1.0;    // of the phase's crystals
  // "cross": {"law": "pericline", "lamella_mm": 0.03}: a second set of lamellae across the first,
  // microcline's cross-hatched grid (section_map.h SectionGrain::CrossTwin); empty law: none.
  std::string cross_law;
  double cross_lamella_mm = 0.0;
};

// A preferred orientation: the habit's prism axis (lineation) or plate normal (foliation pole) of
// each crystal drawn about `direction` (section frame, x east, y north, z up) with a Gaussian
// spread of spread_deg, the rotation about it uniform (nematoblastic amphibole, micas in a
// schist: Passchier & Trouw 2005, Microtectonics, ch. 4).
struct FabricRecipe {
  bool plate_normal = false;
  std::array<double, 3> direction{1.0, 0.0, 0.0};
  double spread_deg = 15.0;
};

// Undulose extinction: every crystal of the phase bent about a random axis and polygonized into
// subgrain bands subgrain_mm wide, step_deg apart across each tilt wall (section_map.h "subgrains";
// Passchier & Trouw 2005, Microtectonics, §3.4 and §3.7).
struct UnduloseRecipe {
  double subgrain_mm = 0.05;
  double step_deg = 1.5;
};

// Alteration along the cracks: a fraction of the phase's crystals have their cracks filled with a
// secondary mineral in veins vein_mm wide (serpentine along olivine's fractures; section_map.h).
struct AlterationRecipe {
  std::string mineral;
  double vein_mm = 0.02;
  double fraction = 1.0;
  // "orientation": "random" (default: the secondary mineral grew in the cracks, serpentine in
  // olivine's fractures) or "host": it replaced the host topotactically, its lattice in the host's
  // orientation (chlorite after biotite, basal layers parallel: Veblen & Ferry 1983, Am. Mineral.
  // 68, 1160–1168).
  bool host_orientation = false;
};

// Inclusions the phase's crystals grew round (section_map.h SectionGrain::InclusionSet): small
// crystals of `mineral` on trails trail_spacing_mm apart, one site every spacing_mm, each occupied
// with probability `fraction`, within growth fraction `within` of the core (1, the default: the
// whole grain, the gaps it filled after its faces stopped included). trail_deg (section
// frame, counter-clockwise from east) is the external foliation the porphyroblast overgrew; absent,
// each crystal's trails take a random direction (sericite dusting a core). rotation_deg is the turn
// of a crystal of the CSD's largest size while it grew: all grew at one rate until the end (the
// growth model), so a crystal of size L grew for a time ∝ L and turned rotation_deg·L/max_mm
// (Rosenfeld 1970). Each crystal's inclusions take `orientations` random orientations.
// A pleochroic halo round each inclusion (section_map.h SectionGrain::InclusionSet::Halo): the host
// within radius_mm of the inclusion's centre absorbs `darkening` times as strongly. The reader
// keeps radius_mm beyond the inclusion's half-length (else nothing shows) and within both
// spacings (a halo then lies in its inclusion's cell or the next, where the lookup searches).
struct HaloRecipe {
  static constexpr double kMaxDarkening = 100.0;
  double radius_mm = 0.0, darkening = 1.0;
};
HaloRecipe read_halo(const JsonReader& h, double size_mm, double spacing_mm, double trail_spacing_mm);

// An inclusion set's "habit": "trail" (the default: each inclusion an ellipse along its trail),
// "needle" (each a prism along its own crystal's elongation, section_map.h InclusionSet::Needle)
// or "wedge" (each a triangle along its trail, its base at the trail's back and its apex ahead:
// the cuneiform quartz of a graphic intergrowth, section_map.h InclusionSet::wedges).
// A needle's mineral needs its elongation and optical orientation in the library (to lay the
// prism in the indicatrix's frame), and the needle may be no longer than either spacing: lying
// any way, it is then found from its cell's eight neighbours.
enum class InclusionHabit { Trail, Needle, Wedge };
InclusionHabit read_inclusion_habit(const JsonReader& a, const std::string& mineral, double size_mm,
                                    double trail_spacing_mm);
const char* inclusion_habit_name(InclusionHabit h);  // "trail", "needle", "wedge"

struct InclusionRecipe {
  // The limits both readers enforce (this recipe's and a section file's, section_map.cpp): an
  // inclusion no longer than its site spacing or wider than its trail spacing, so each cell holds
  // at most one; at most kMaxOrientations domains per grain.
  static constexpr double kMaxSizeMm = 1.0, kMaxAspect = 20.0, kMaxSpacingMm = 5.0;
  static constexpr double kMaxTrailDeg = 360.0, kMaxRotationDeg = 720.0;
  static constexpr int kMaxOrientations = 64;
  std::string mineral;
  double size_mm = 0.03, aspect = 1.0, spacing_mm = 0.1, trail_spacing_mm = 0.1;
  double fraction = 1.0, within = 1.0, rotation_deg = 0.0;
  std::optional<double> trail_deg;
  int orientations = 4;
  InclusionHabit habit = InclusionHabit::Trail;
  std::optional<HaloRecipe> halo;
};

// Syntaxial overgrowth cement on a rounded phase's grains (overgrowth_cement.h): cement_percent of
// the section, taken from the pores, in lattice continuity with each grain; the grains' forms all
// at one habit_scale, the one that puts that much cement in the section (grow_rock calibrates it).
// With a dust line of isotropic specks (fluid inclusions) on the detrital surface it grew over.
struct DustLineRecipe {
  std::string mineral;
  double size_mm = 0.004, spacing_mm = 0.008, fraction = 1.0;
};
struct OvergrowthRecipe {
  double cement_percent = 5.0;
  std::optional<DustLineRecipe> dust;
};

// Myrmekite on a phase's grains (myrmekite.h): bulbs into the grains of the host mineral, each
// grain's quartz rods in one orientation of their own.
struct MyrmekiteRecipe {
  // Bounds a recipe and a section file both hold a myrmekite to (rock_recipe.cpp, section_map.cpp).
  static constexpr double kMaxDepthMm = 1.0, kMaxBulbMm = 2.0, kMaxRodWidthMm = 0.1, kMaxRodSpacingMm = 0.5;
  std::string host;
  double depth_mm = 0.1, bulb_mm = 0.2, fraction = 1.0;
  std::string quartz_mineral = "quartz";
  double rod_width_mm = 0.005, rod_spacing_mm = 0.015;
};

struct PhaseRecipe {
  std::string name, mineral;
  double mode_percent = 0.0;
  CsdRecipe csd;
  double nucleation = 0.0;
  std::optional<double> aspect;
  // Detrital grains rounded by transport: balls of the CSD's sizes instead of the habit polyhedron
  // (a sandstone's framework; with a matrix, the pores between them).
  bool rounded = false;
  // A porphyroblast replaces the matrix grains in its way (grown_tiling.h, GrainGrowth::overgrows):
  // its free-growth shape is its own, whatever matrix crystal nucleated inside it.
  bool porphyroblast = false;
  std::optional<ZoningRecipe> zoning;
  std::optional<TwinRecipe> twin;
  std::optional<FabricRecipe> fabric;
  std::optional<UnduloseRecipe> undulose;
  std::optional<AlterationRecipe> alteration;
  std::optional<InclusionRecipe> inclusions;
  std::optional<OvergrowthRecipe> overgrowth;
  std::optional<MyrmekiteRecipe> myrmekite;
};

// A granoblastic rock (quartzite, marble): grains that recrystallised together into a foam of
// nearly equal grains meeting at ~120° (foam_relaxation.h). The phases then give minerals and
// modes (no CSD: relaxation makes the sizes nearly equal); every cell takes a phase at random
// in proportion to the modes.
struct GranoblasticRecipe {
  double grain_mm = 0.3;     // the cells' mean equivalent-sphere diameter
  int relax_iterations = 12; // Lloyd steps; 0 keeps the Poisson–Voronoi aggregate
};

struct RockRecipe {
  std::string path, name, source, texture;
  std::optional<GranoblasticRecipe> granoblastic;
  std::uint64_t seed = 1;
  double width_mm = 8.0, height_mm = 6.0, thickness_um = 30.0;
  std::string matrix_mineral;  // empty: holocrystalline, the crystals fill the rock
  std::vector<PhaseRecipe> phases;
};

// Throws InputError naming file, key and value on a malformed recipe, an unknown mineral, modes
// that do not sum to ≤ 100 (to 100 without a matrix), or a CSD whose range is empty.
RockRecipe read_rock_recipe(const std::string& path);

// The recipe file for a rock name (assets/rocks/<name>.json) or a path to a file whose "type" is
// "rock"; "" when it is neither.
std::string rock_recipe_path(const std::string& name_or_path);

}  // namespace pmsim
