// evaluate_unit_in_trains (core/render/spectral_level.h): one band loop a direction serves several
// polarizing trains, because the modal band sum regroups by anchor into terms that depend on the
// fit's Γ alone. Checked against evaluate_unit on plans compiled at each train, on a quartz wedge
// (units at many thickness steps: thickness scales ≠ 1) lit by the whole condenser cone (several
// directions a unit), and on a biaxial figure.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/microscope/compensator.h"
#include "core/microscope/evaluation_plan.h"
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

}  // namespace
