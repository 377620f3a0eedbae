// A uniaxial plate cut ⟂ its optic axis is symmetric about the stage normal, so compile_evaluation_plan fits
// its conoscopic figure from a radial table of modal fits instead of three mode solutions per pixel. The
// table must reproduce the per-direction fits (Γ and the mode amplitudes) and the image.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/microscope/evaluation_plan.h"
#include "core/render/image_develop.h"
#include "core/render/progressive_renderer.h"
#include "core/render/spectral_level.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "tests/asset_scene.h"
#include "tests/modal_table_support.h"

using namespace pmsim;

namespace {

Scene calcite_figure(int size, double stage_deg) {
  Scene s = asset_scene("calcite_cono.json");  // calcite 1 mm ⟂ c, NA 0.85, condenser 0.9
  s.render.width = s.render.height = size;
  s.optics.lens_model = LensModel::Ideal;
  s.stage_deg = stage_deg;
  return s;
}

using test::image_difference;
using test::per_direction_fits;

TEST(RadialModalTable, CalciteFigureFitsMatchPerDirectionFits) {
  for (double stage : {0.0, 33.0}) {
    const auto plan = compile_evaluation_plan(calcite_figure(96, stage));
    ASSERT_NE(plan->model_report().find("radial table"), std::string::npos) << plan->model_report();
    const EvaluationPlan direct = per_direction_fits(*plan);
    double max_dgamma = 0.0, max_dc = 0.0;
    for (std::size_t u = 0; u < plan->units().size(); ++u)
      for (int a = 0; a < 3; ++a) {
        max_dgamma = std::max(
            max_dgamma, std::fabs(plan->modal_terms()[u].gamma_nm[a] - direct.modal_terms()[u].gamma_nm[a]));
        for (int k = 0; k < 5; ++k)
          max_dc =
              std::max(max_dc, std::fabs(plan->modal_terms()[u].c[k][a] - direct.modal_terms()[u].c[k][a]));
      }
    // Linear interpolation in sin²θ over 1025 entries: h²/8·|Γ''| ≈ 0.01 nm for Γ ≤ 1.7e5 nm;
    // 0.05 nm of Γ is 8e-4 rad of phase at 400 nm, invisible.
    EXPECT_LT(max_dgamma, 0.05) << "stage " << stage;
    std::printf("stage %g: max dGamma %.3g nm, max dC %.3g\n", stage, max_dgamma, max_dc);
    // The mode amplitudes are exactly radial/tangential by symmetry; the coefficients are products
    // of amplitudes ≤ 1, so 1e-6 is far below an 8-bit grey level (4e-3).
    EXPECT_LT(max_dc, 1e-6) << "stage " << stage;
  }
}

TEST(RadialModalTable, CalciteFigureImageUnchanged) {
  // 512² behind PMSIM_LONG (a few seconds); 128² otherwise.
  const int size = std::getenv("PMSIM_LONG") ? 512 : 128;
  const auto plan = compile_evaluation_plan(calcite_figure(size, 0.0));
  const EvaluationPlan direct = per_direction_fits(*plan);
  // The issue allows 0.1 CIEDE2000 of change in the converged image for speed-ups.
  const double de = image_difference(*plan, direct, 32);
  std::printf("mean CIEDE2000 table vs per-direction fits at %d^2: %.4f\n", size, de);
  EXPECT_LT(de, 0.1);
}

TEST(RadialModalTable, TiltedOpticAxisUsesPerDirectionFits) {
  Scene s = calcite_figure(96, 0.0);
  s.sample.optic_axis = {0.0, std::sin(0.2), std::cos(0.2)};  // not symmetric about the stage normal
  const auto plan = compile_evaluation_plan(s);
  EXPECT_EQ(plan->model_report().find("radial table"), std::string::npos) << plan->model_report();
}

}  // namespace
