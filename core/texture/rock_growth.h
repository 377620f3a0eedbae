#pragma once
// The texture engine: grows a rock from its recipe (rock_recipe.h) and a seed, and cuts the thin
// section through it (section z = 0).
//
// Each phase nucleates crystals from its start in the order of crystallisation and grows them at
// one constant linear rate G until the rock is quenched (time 1), so a crystal of free size L
// nucleated at 1 − L/G. Sizes follow the phase's log-linear CSD: the population of steady
// nucleation and size-independent growth (Marsh 1988, Contrib. Mineral. Petrol. 99, 277–291).
// Crystals that cut the section plane are drawn directly: their number is the volume density
// times the section area times the mean caliper 2R·E[L] (R: circumradius per unit size), their
// sizes length-biased (a larger crystal is cut more often), the nucleus height uniform within R·L
// of the plane. Each crystal takes its habit polyhedron in a uniformly random orientation; the
// section point is owned by the crystal that reaches it first (grown_tiling.h).
//
// Impingement takes volume from late phases, so the densities are calibrated: from the mode over
// the mean crystal volume, then scaled by target / measured area fraction (Delesse: area
// fraction = volume fraction) until every phase is within kModeTolerance. Without a matrix the
// fractions sum to 1 and the same scaling balances them.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json_fwd.hpp>

#include "core/texture/rock_recipe.h"

namespace pmsim {

// Calibration stops when every phase's area fraction is within this of its mode (absolute, as a
// fraction: 1 vol%), or within its sampling error when that is larger (few, large crystals).
inline constexpr double kModeTolerance = 0.01;
// Near saturation (a glass-poor basalt: 88 % crystals capped at their free size) a phase's
// fraction grows more slowly than its density and the ratio steps undershoot: the basalt settles in
// 7–8 rounds; the other shipped rocks in 2–4.
inline constexpr int kMaxCalibrationRounds = 10;

// A section larger than this (mm², the shipped 8 × 6 mm) is calibrated on a centred window of this
// area before the whole is drawn: four rounds over 1.8 million andesite microlites at 20 × 15 mm
// took 20 s, four over the window and one over the whole a fraction of it.
inline constexpr double kCalibrationWindowMm2 = 48.0;

struct GrownCrystal {
  int phase = 0;
  glm::dvec3 nucleus_mm{0.0};
  double size_mm = 0.0;  // free-growth size (longest dimension)
  double from = 0.0;     // nucleation time (the quench is at 1)
  std::array<double, 3> euler_deg{};
  bool twinned = false;
  double area_mm2 = 0.0;  // of the section it owns (0: overgrown, or it missed the plane)
};

struct RockGrowth {
  // Every crystal drawn (the nucleation–growth population whose free sizes follow the CSD); those
  // with area_mm2 > 0 are the section's grains.
  std::vector<GrownCrystal> crystals;
  std::vector<double> area_fraction;   // per phase, then the matrix (with cement: pores and cement), on the measuring raster
  // Per phase: the sampling error of its area fraction in a section this size, √(Σ aᵢ²) / A over
  // its grains' areas aᵢ (a Poisson count of grains, each carrying its area): what one section
  // can tell of the mode. A few large phenocrysts make it several per cent.
  std::vector<double> sampling_error;
  std::vector<double> density_per_mm3; // per phase, after calibration
  // Per phase: the habit_scale of its grains' overgrowths (overgrowth_cement.h; 0: none) and the
  // area fraction of the cement they put in the pores, on measure_areas' raster.
  std::vector<double> overgrowth_scale, cement_fraction;
  int rounds = 0;                      // calibration rounds over the whole section
  int window_rounds = 0;               // before them, over the calibration window (0: none)
};

RockGrowth grow_rock(const RockRecipe& recipe, std::uint64_t seed);

// The section file (docs/sections.md, grains with "growth") of a grown rock.
nlohmann::json rock_section_json(const RockRecipe& recipe, const RockGrowth& growth, std::uint64_t seed);

// The same file in pieces: its keys without "grains", then each grain in file order (the matrix
// last), for a reader that parses a grain as it comes (section_from_grown_rock): a 20 × 15 mm
// andesite's 0.4 million grains are 0.7 GB as one JSON value.
nlohmann::json rock_section_header_json(const RockRecipe& recipe, std::uint64_t seed);
void for_each_rock_grain_json(const RockRecipe& recipe, const RockGrowth& growth, std::uint64_t seed,
                              const std::function<void(const nlohmann::json&)>& grain);

// The same grains by index, for a reader that parses them in parallel: grain(k) may be asked from
// any thread in any order and is the k-th grain for_each_rock_grain_json writes. A serial pass
// first notes each grain's crystal and where its random draws (subgrains, alteration, inclusions)
// start in the file's one random sequence.
class RockGrainsJson {
 public:
  RockGrainsJson(const RockRecipe& recipe, const RockGrowth& growth, std::uint64_t seed);
  std::size_t size() const { return crystal_.size() + (recipe_.matrix_mineral.empty() ? 0 : 1); }
  nlohmann::json grain(std::size_t k) const;

 private:
  const RockRecipe& recipe_;
  const RockGrowth& growth_;
  std::uint64_t seed_;
  std::vector<std::uint32_t> crystal_;      // per grain but the matrix: its crystal
  std::vector<std::uint64_t> random_state_;  // per grain: the random sequence's state before its draws
};

}  // namespace pmsim
