// A conoscopic figure of one plate is a function of the direction alone, so compile_evaluation_plan
// fits a large figure of a biaxial (or tilted uniaxial) plate from a table of modal fits over the
// direction instead of three mode solutions per pixel. The table must reproduce the per-direction
// fits (Γ and the interference coefficients) and the image, and small figures must keep their
// per-pixel fits (the golden images are 96²).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/microscope/direction_modal_table.h"
#include "core/microscope/evaluation_plan.h"
#include "core/render/image_develop.h"
#include "core/render/spectral_level.h"
#include "tests/asset_scene.h"
#include "tests/modal_table_support.h"

using namespace pmsim;

namespace {

Scene figure(const char* file, int size) {
  Scene s = asset_scene(file);
  s.render.width = s.render.height = size;
  s.optics.lens_model = LensModel::Ideal;
  return s;
}

using test::image_difference;
using test::per_direction_fits;

void expect_matches_per_direction_fits(const Scene& s, const char* what) {
  const auto plan = compile_evaluation_plan(s);
  ASSERT_NE(plan->model_report().find("direction table"), std::string::npos) << what << plan->model_report();
  const EvaluationPlan direct = per_direction_fits(*plan);
  double max_dgamma = 0.0, max_dc = 0.0;
  for (std::size_t u = 0; u < plan->units().size(); ++u)
    for (int a = 0; a < 3; ++a) {
      max_dgamma = std::max(max_dgamma,
                            std::fabs(plan->modal_terms()[u].gamma_nm[a] - direct.modal_terms()[u].gamma_nm[a]));
      if (direct.modal_terms()[u].gamma_nm[a] < 20.0) continue;  // see below
      for (int k = 0; k < 5; ++k)
        max_dc = std::max(max_dc, std::fabs(plan->modal_terms()[u].c[k][a] - direct.modal_terms()[u].c[k][a]));
    }
  std::printf("%s: max dGamma %.3g nm, max dC %.3g\n", what, max_dgamma, max_dc);
  // The table's own check bounds |ΔB| ≤ 0.5 nm at cell centres (0.008 rad of phase at 400 nm);
  // every pixel must be within it.
  EXPECT_LT(max_dgamma, 0.5) << what;
  // The coefficients are products of mode amplitudes ≤ 1: 2e-3 is half an 8-bit grey level. Near
  // an optic axis (Γ < 20 nm) the modes turn fast and their interpolated directions are worse,
  // but there T = (C0 + Cφ) − Cφ·(1 − cos φ) with C0 + Cφ independent of the modes and
  // 1 − cos φ < 0.03, so a 0.01 error of Cφ moves T by < 3e-4: not counted.
  EXPECT_LT(max_dc, 2e-3) << what;
  // The issue allows 0.1 CIEDE2000 of change in the converged image for speed-ups.
  const double de = image_difference(*plan, direct, 32);
  std::printf("%s: mean CIEDE2000 table vs per-direction fits %.4f\n", what, de);
  EXPECT_LT(de, 0.1) << what;
}

TEST(DirectionModalTable, BiaxialFigureMatchesPerDirectionFits) {
  // Muscovite 60 µm, acute bisectrix ⟂ stage, stage 45°: both melatopes inside NA 0.85.
  expect_matches_per_direction_fits(figure("muscovite_cono.json", 160), "muscovite Bxa 160^2");
}

TEST(DirectionModalTable, TiltedUniaxialFigureMatchesPerDirectionFits) {
  Scene s = figure("calcite_cono.json", 160);
  s.sample.thickness_um = 10.0;  // Γ up to ~1.7e3 nm (1 mm: see RefusesWhereItsCheckFails)
  s.sample.optic_axis = {0.0, std::sin(0.2), std::cos(0.2)};
  expect_matches_per_direction_fits(s, "calcite 10 um tilted 11.5 deg 160^2");
}

TEST(DirectionModalTable, RefusesWhereItsCheckFails) {
  // Calcite 1 mm tilted: Γ up to 1.7e5 nm, whose curvature over a 48-cell grid is beyond the
  // 0.5 nm the check allows; the figure keeps its per-pixel fits.
  Scene s = figure("calcite_cono.json", 160);
  s.sample.optic_axis = {0.0, std::sin(0.2), std::cos(0.2)};
  PreparedPlate anchors[3];
  const auto plan = compile_evaluation_plan(s);
  EXPECT_EQ(plan->model_report().find("direction table"), std::string::npos) << plan->model_report();
  for (int a = 0; a < 3; ++a) anchors[a] = plan->prepare(0, ModalFit::kAnchorNm[a]);
  DirectionModalTable t;
  EXPECT_FALSE(t.build(anchors, 0.85));
  std::printf("calcite 1 mm tilted: check |dB| %.3g nm\n", t.checked_b_error_nm());
  EXPECT_GT(t.checked_b_error_nm(), 0.5);
}

TEST(DirectionModalTable, SmallFiguresKeepPerPixelFits) {
  // 96² (the golden images): ~7 200 units, fewer than 4× the table's fits.
  const Scene s = figure("muscovite_cono.json", 96);
  EXPECT_GT(4 * DirectionModalTable::nodes_needed(0.85), 96 * 96 * 0.79);
  const auto plan = compile_evaluation_plan(s);
  EXPECT_EQ(plan->model_report().find("direction table"), std::string::npos) << plan->model_report();
}

}  // namespace
