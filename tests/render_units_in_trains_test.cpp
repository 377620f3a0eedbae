// evaluate_unit_in_trains (core/render/spectral_level.h): one band loop a direction serves several
// polarizing trains, because the modal band sum regroups by anchor into terms that depend on the
// fit's Γ alone. Checked against evaluate_unit on plans compiled at each train, on a quartz wedge
// (units at many thickness steps: thickness scales ≠ 1) lit by the whole condenser cone (several
// directions a unit), and on a biaxial figure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/microscope/compensator.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/optical_train.h"
#include "core/render/compensator_sums.h"
#include "core/render/spectral_level.h"

using namespace pmsim;

namespace {

// The conoscope without the Bertrand lens: the image plane lit by the whole illuminating cone, so
// every unit integrates over the cone's directions.
Scene wedge() {
  Scene s;
  s.mode = ViewMode::Cono;
  s.bertrand_in = false;
  s.render.width = 48;
  s.render.height = 8;
  s.render.spp = 8;
  s.condenser.na = 0.3;
  s.sample.type = SampleType::Wedge;
  s.sample.mineral = "quartz";
  s.sample.thickness_um = 200.0;
  s.sample.optic_axis = {0.70710678, 0.70710678, 0.0};
  return s;
}

Scene biaxial_figure() {
  Scene s;
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  s.objective.na = 0.85;
  s.condenser.na = 0.9;
  s.render.width = s.render.height = 24;
  s.sample.mineral = "muscovite";
  s.sample.thickness_um = 40.0;
  s.sample.optic_axis = {0.0, 0.0, 1.0};
  return s;
}

struct Polars {
  double polarizer_deg, analyzer_deg;
  bool analyzer_in;
};

struct Coverage {
  int units = 0, several_dirs = 0, scaled = 0;
};

Coverage check_trains(const Scene& scene, int bands) {
  const std::vector<Polars> polars = {{0.0, 90.0, true}, {10.0, 100.0, true}, {45.0, 0.0, true}, {30.0, 0.0, false}};
  std::vector<Scene> scenes;
  std::vector<TrainState> trains;
  for (const Polars& p : polars) {
    Scene s = scene;
    s.polarizer_deg = p.polarizer_deg;
    s.analyzer_deg = p.analyzer_deg;
    s.analyzer_in = p.analyzer_in;
    scenes.push_back(s);
    trains.push_back(make_train(s, make_compensator(s.compensator, s.compensator_position), 550.0));
  }
  const auto shared = compile_evaluation_plan(scenes[0], nullptr, true);
  EXPECT_TRUE(shared);
  if (!shared) return {};
  EXPECT_EQ(shared->modal_fits().size(), shared->modal_terms().size());
  const SpectralLevel level = make_spectral_level(*shared, bands);
  const int units = static_cast<int>(shared->units().size());
  int several_dirs = 0, scaled = 0;
  for (int u = 0; u < units; ++u) {
    const EvalUnit& unit = shared->units()[u];
    several_dirs += shared->dirs_of(unit) > 1;
    scaled += std::fabs(unit.thickness_um - shared->domains()[unit.domain].thickness_um) > 1e-9;
  }
  std::printf("%d units, %d with several directions, %d at a scaled thickness\n", units, several_dirs, scaled);
  double worst = 0.0;
  for (std::size_t t = 0; t < scenes.size(); ++t) {
    const auto own = compile_evaluation_plan(scenes[t]);
    const SpectralLevel own_level = make_spectral_level(*own, bands);
    EXPECT_EQ(static_cast<int>(own->units().size()), units);
    for (int u = 0; u < units && u < static_cast<int>(own->units().size()); ++u) {
      EXPECT_TRUE(shares_band_loop(*shared, level, u));
      glm::dvec3 v[4];
      evaluate_unit_in_trains(*shared, level, u, trains, v);
      const glm::dvec3 ref = evaluate_unit(*own, own_level, u);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(v[t][c] - ref[c]));
    }
  }
  std::printf("max |ΔXYZ| against each train's own plan: %.2e\n", worst);
  // The same terms summed in another order: sums of ≤ 256 band terms of size ≤ ~1 in double
  // differ by ~n·2⁻⁵² ≈ 6e-14; 1e-10 leaves a wide margin, while a wrong train or anchor would
  // be off by 1e-2 or more (the polars change the image by tens of per cent).
  EXPECT_LT(worst, 1e-10);
  return {units, several_dirs, scaled};
}

TEST(UnitsInTrains, WedgeUnderACondenserConeIsEachTrainsOwnEvaluation) {
  const Coverage c = check_trains(wedge(), 32);
  EXPECT_EQ(c.several_dirs, c.units);  // what the test is for: the cone's directions and
  EXPECT_EQ(c.scaled, c.units - 1);    // every thickness step but the fitted one
}

TEST(UnitsInTrains, BiaxialFigureIsEachTrainsOwnEvaluation) { check_trains(biaxial_figure(), 64); }

// evaluate_unit_in_train: one unit in a train with an accessory, from the fits of a plan compiled
// without one (a flat view's frames with the gypsum plate or the wedge, figure_response.h).
struct Slot {
  Compensator kind;
  double position, polarizer_deg, analyzer_deg;
  bool analyzer_in;
};
const Slot kSlots[] = {{Compensator::Gypsum, 0.0, 10.0, 100.0, true},
                       {Compensator::QuartzWedge, 0.7, 45.0, 0.0, true},
                       {Compensator::Mica, 0.0, 30.0, 0.0, false}};

Scene in_slot(Scene s, const Slot& slot) {
  s.compensator = slot.kind;
  s.compensator_position = slot.position;
  s.polarizer_deg = slot.polarizer_deg;
  s.analyzer_deg = slot.analyzer_deg;
  s.analyzer_in = slot.analyzer_in;
  return s;
}

// Every unit of `plain` (compiled without an accessory, its fits kept; its stage at 0°) in the
// slot's train turned by the stage of `with_slot`, against evaluate_unit on the plan compiled for
// `with_slot` itself. Returns the largest |ΔXYZ|.
double slot_against_own_plan(const Scene& plain, const Scene& with_slot, int bands) {
  const auto shared = compile_evaluation_plan(plain, nullptr, true);
  const auto own = compile_evaluation_plan(with_slot);
  EXPECT_TRUE(shared && own);
  if (!shared || !own) return INFINITY;
  EXPECT_EQ(own->units().size(), shared->units().size());
  const CompensatorPlate comp = make_compensator(with_slot.compensator, with_slot.compensator_position);
  Scene lab = with_slot;
  lab.stage_deg = 0.0;
  const double theta = with_slot.stage_deg * 3.14159265358979323846 / 180.0;
  SpectralLevel level = level_in_train(make_spectral_level(*shared, bands), lab, comp);
  for (TrainState& t : level.train) t = train_in_specimen_frame(t, theta);
  const TrainState train = train_in_specimen_frame(make_train(lab, comp, 550.0), theta);
  const SpectralLevel own_level = make_spectral_level(*own, bands);
  double worst = 0.0;
  for (std::size_t u = 0; u < own->units().size() && u < shared->units().size(); ++u) {
    const glm::dvec3 v = evaluate_unit_in_train(*shared, level, train, static_cast<int>(u));
    const glm::dvec3 ref = evaluate_unit(*own, own_level, static_cast<int>(u));
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(v[c] - ref[c]));
  }
  return worst;
}

TEST(UnitsInTrains, AnAccessorysTrainFromPlainFitsIsItsOwnPlans) {
  for (const Slot& slot : kSlots) {
    const double worst = slot_against_own_plan(wedge(), in_slot(wedge(), slot), 32);
    std::printf("wedge, accessory %d: max |ΔXYZ| %.2e\n", static_cast<int>(slot.kind), worst);
    // The same fits, the same terms (make_modal_terms in the slot's train) and the same band loop:
    // measured 0 here; a band sum in another order would differ by ~1e-15. The bands' trains without
    // the accessory's phase χ were measured 0.57 (gypsum) and 1.9e-3 (wedge) off; the mica case,
    // analyzer out, hardly sees the slot at all and guards the analyzer-out train.
    EXPECT_LT(worst, 1e-10);
  }
}

// Turning the stage by θ is turning the polars and the slot by −θ: a plate at stage θ in the lab's
// train transmits what the plate at stage 0° does in the train turned into its frame. In parallel
// light (one direction, along the axis) this is exact, up to rounding in the turned crystal's
// fits; quartz (modal) and biotite (absorbing: exact, band by band in the turned Jones matrices).
TEST(UnitsInTrains, ATurnedStageIsTheTrainTurnedTheOtherWay) {
  for (const char* mineral : {"quartz", "biotite"}) {
    Scene plate;
    plate.sample.mineral = mineral;
    plate.sample.optic_axis = {0.8, 0.6, 0.0};
    plate.sample.x_axis = {0.0, 0.0, 1.0};  // biotite: nα across the plate, nγ in it at 37°
    plate.sample.z_axis = {0.8, 0.6, 0.0};
    plate.render.width = plate.render.height = 8;
    for (const Slot& slot : kSlots)
      for (const double stage : {0.0, 33.0, 117.0}) {
        Scene turned = in_slot(plate, slot);
        turned.stage_deg = stage;
        const double worst = slot_against_own_plan(plate, turned, 32);
        std::printf("%s at stage %.0f°, accessory %d: max |ΔXYZ| %.2e\n", mineral, stage, static_cast<int>(slot.kind),
                    worst);
        // The turned crystal's modes differ from the unturned ones' turned by θ in the last few
        // bits of each eigen-solution: measured ≤ 1.4e-14. With the train turned the wrong way
        // (+θ) it was 0.28–0.87 for quartz with the gypsum plate or the wedge (addition becomes
        // subtraction), 6e-3–1e-2 for biotite, and 0.9–15e-6 with the analyzer out (mica): 1e-9
        // sits 10⁴ above the rounding and ≥ 10² below the smallest of those.
        EXPECT_LT(worst, 1e-9);
      }
  }
}

// compensator_sums: the general band loop regrouped by term and anchor, its sums made once in the
// slot's unturned train and read at every stage: each unit as evaluate_unit_in_train gives it in
// the train turned into the specimen's frame. On the cone-lit wedge (several directions a unit,
// thickness scales ≠ 1) and a biaxial figure, with each accessory, in bands; at one line the plans
// take every unit exact, and both go band by band (measured 0).
TEST(UnitsInTrains, ACompensatorsSumsAreItsBandLoopRegrouped) {
  for (const bool figure : {false, true})
    for (const bool line : {false, true})
      for (const Slot& slot : kSlots) {
        Scene plain = figure ? biaxial_figure() : wedge();
        if (line) plain.render.single_wavelength_nm = 589.0;
        const auto plan = compile_evaluation_plan(plain, nullptr, true);
        ASSERT_TRUE(plan);
        Scene lab = in_slot(plain, slot);
        const CompensatorPlate comp = make_compensator(lab.compensator, lab.compensator_position);
        const SpectralLevel level = level_in_train(make_spectral_level(*plan, 32), lab, comp);
        const CompensatorSums sums = compensator_sums(*plan, level);
        ASSERT_FALSE(sums.dirs.empty());
        double worst = 0.0, largest = 0.0;
        for (const double stage : {0.0, 117.0}) {
          const double theta = stage * 3.14159265358979323846 / 180.0;
          SpectralLevel turned = level;
          for (TrainState& t : turned.train) t = train_in_specimen_frame(t, theta);
          const TrainState train = train_in_specimen_frame(make_train(lab, comp, 550.0), theta);
          for (int u = 0; u < static_cast<int>(plan->units().size()); ++u) {
            const glm::dvec3 v = evaluate_unit_from_sums(*plan, turned, train, sums, u);
            const glm::dvec3 ref = evaluate_unit_in_train(*plan, turned, train, u);
            for (int c = 0; c < 3; ++c) {
              worst = std::max(worst, std::fabs(v[c] - ref[c]));
              largest = std::max(largest, std::fabs(ref[c]));
            }
          }
        }
        int exact = 0;
        for (int u = 0; u < static_cast<int>(plan->units().size()); ++u) exact += plan->needs_exact(u);
        std::printf("%s%s, accessory %d: max |ΔXYZ| %.2e (largest |XYZ| %.2f; %d of %zu units exact)\n",
                    figure ? "figure" : "wedge", line ? " at 589 nm" : "", static_cast<int>(slot.kind), worst, largest,
                    exact, plan->units().size());
        // The same band terms summed in another order, the sums stored in float (relative 6e-8)
        // and combined with coefficients of order 1 over ~15 products: a few 1e-7 of XYZ ≤ ~2.
        // 1e-5 leaves a margin of 10 and is far below the 0.57 the phase χ left out would cost
        // (AnAccessorysTrainFromPlainFitsIsItsOwnPlans).
        EXPECT_LT(worst, 1e-5);
      }
}

}  // namespace
