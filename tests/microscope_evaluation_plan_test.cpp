// The stages of an evaluation plan, each on its own: the specimen's domains, the views, the model
// policy, the radial table of modal fits, and the two shared conversions (dmat2 → Jones, L*).
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "core/microscope/evaluation_plan.h"
#include "core/microscope/model_policy.h"
#include "core/microscope/optical_domains.h"
#include "core/microscope/pixel_view.h"
#include "core/microscope/radial_modal_table.h"
#include "core/microscope/view_geometry.h"
#include "core/optics/jones.h"
#include "core/spectrum/color.h"

using namespace pmsim;

namespace {

Scene calcite_figure(int size) {
  Scene s;
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  s.objective.na = 0.85;
  s.condenser.na = 0.6;  // smaller than the objective's: the lit disk is inside the field
  s.render.width = s.render.height = size;
  s.optics.lens_model = LensModel::Ideal;
  s.sample.mineral = "calcite";
  s.sample.thickness_um = 1000.0;
  s.sample.optic_axis = {0, 0, 1};
  return s;
}

Scene quartz_plate(int size) {
  Scene s;
  s.mode = ViewMode::Ortho;
  s.bertrand_in = false;
  s.render.width = s.render.height = size;
  s.sample.mineral = "quartz";
  s.sample.thickness_um = 30.0;
  return s;
}

}  // namespace

TEST(OpticalDomains, SectionDomainsAreSlideMediumThenEachGrainsZonesAndTwins) {
  Scene s = quartz_plate(8);
  s.sample.type = SampleType::Section;
  s.sample.section = "gabbro";  // grown: normally zoned, albite-twinned plagioclase
  const OpticalDomains d = optical_domains(s);
  ASSERT_NE(d.section, nullptr);
  ASSERT_GT(d.section->grains.size(), 1u);
  EXPECT_EQ(d.domains[SectionMap::kSlideDomain].crystal, nullptr);
  EXPECT_EQ(d.domains[SectionMap::kMediumDomain].crystal, nullptr);
  std::size_t expected = 2;
  bool zoned = false, twinned = false;
  for (const SectionGrain& g : d.section->grains) {
    const int per_zone = g.twinned ? 2 : 1;
    ASSERT_EQ(g.first_domain, static_cast<int>(expected));
    for (std::size_t z = 0; z < g.zones.size(); ++z)
      for (int t = 0; t < per_zone; ++t)
        EXPECT_EQ(d.domains[g.first_domain + z * per_zone + t].mineral, g.zones[z].mineral);
    EXPECT_EQ(g.zones.front().mineral, g.mineral);
    expected += g.zones.size() * per_zone;
    zoned |= g.zones.size() > 1;
    twinned |= g.twinned;
  }
  EXPECT_EQ(d.domains.size(), expected);
  EXPECT_TRUE(zoned);
  EXPECT_TRUE(twinned);
}

TEST(OpticalDomains, PlateAndEmptyStageAreOneDomain) {
  const Scene plate = quartz_plate(8);
  const OpticalDomains d = optical_domains(plate);
  ASSERT_EQ(d.domains.size(), 1u);
  EXPECT_EQ(d.domains[0].mineral, "quartz");
  EXPECT_EQ(d.domain_at_sample({0.3, -0.2}), 0);
  Scene empty = plate;
  empty.sample_in = false;
  const OpticalDomains e = optical_domains(empty);
  ASSERT_EQ(e.domains.size(), 1u);
  EXPECT_EQ(e.domains[0].crystal, nullptr);
}

TEST(PixelView, ConoscopicFigureLightsExactlyThePixelsInsideTheAperture) {
  const Scene s = calcite_figure(48);
  const std::optional<PixelView> view = conoscopic_figure_view(s, optical_domains(s));
  ASSERT_TRUE(view);
  EXPECT_EQ(view->kind, ViewKind::ConoscopicFigure);
  ASSERT_EQ(view->pixel_offset.size(), 48u * 48u + 1u);
  std::size_t lit = 0, dark = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * 48 + x;
      glm::dvec3 k;
      const bool inside = bfp_direction(s, field_from_pixel(48, 48, x + 0.5, y + 0.5), k);
      const int n = view->pixel_offset[i + 1] - view->pixel_offset[i];
      ASSERT_EQ(n, inside ? 1 : 0) << x << "," << y;
      if (!inside) {
        ++dark;
        continue;
      }
      ++lit;
      const PixelRef& r = view->refs[view->pixel_offset[i]];
      EXPECT_EQ(r.weight, 1.0f);
      EXPECT_EQ(view->units[r.unit].k_air, k);  // the pixel's own direction
    }
  EXPECT_EQ(view->units.size(), lit);
  EXPECT_GT(dark, 0u);  // condenser NA < objective NA: the corners and a rim stay dark
}

TEST(PixelView, UniformPlateIsOneEvaluationForTheWholeField) {
  const Scene s = quartz_plate(16);
  const std::optional<PixelView> view = field_view(s, optical_domains(s));
  ASSERT_TRUE(view);
  ASSERT_EQ(view->units.size(), 1u);
  EXPECT_TRUE(view->cone_dirs.empty());  // parallel light
  ASSERT_EQ(view->refs.size(), 16u * 16u);
  for (std::size_t i = 0; i < 16u * 16u; ++i) {
    ASSERT_EQ(view->pixel_offset[i + 1] - view->pixel_offset[i], 1);
    EXPECT_EQ(view->refs[i].unit, 0);
    EXPECT_FLOAT_EQ(view->refs[i].weight, 1.0f);  // one sub-sample (spp 0 on a plate) of weight 1
  }
}

TEST(PixelView, SectionWeightsSumToOnePerPixel) {
  Scene s = quartz_plate(24);
  s.sample.type = SampleType::Section;
  s.sample.section = "basalt";
  const std::optional<PixelView> view = field_view(s, optical_domains(s));
  ASSERT_TRUE(view);
  EXPECT_EQ(view->spatial_samples, 4);  // spp 0 on a section: 2×2 sub-pixel samples
  bool boundary = false;
  for (std::size_t i = 0; i + 1 < view->pixel_offset.size(); ++i) {
    float sum = 0.0f;
    for (int k = view->pixel_offset[i]; k < view->pixel_offset[i + 1]; ++k) sum += view->refs[k].weight;
    boundary = boundary || view->pixel_offset[i + 1] - view->pixel_offset[i] > 1;
    EXPECT_NEAR(sum, 1.0f, 1e-6f);  // four float weights of 1/4: exact up to rounding
  }
  EXPECT_TRUE(boundary);  // some pixel straddles a grain boundary
}

TEST(ModelPolicy, ExactForSingleWavelengthAndForStrategyExact) {
  const auto no_lens_measurement = [](const LensPolarizationTable&) -> double {
    ADD_FAILURE() << "lens difference measured in parallel light";
    return 0.0;
  };
  Scene s = quartz_plate(8);
  EXPECT_EQ(choose_model_policy(s, optical_domains(s).domains, no_lens_measurement).plate_model,
            PlateModel::Modal);
  s.render.strategy = RenderStrategy::Exact;
  EXPECT_EQ(choose_model_policy(s, optical_domains(s).domains, no_lens_measurement).plate_model,
            PlateModel::Exact);
  s.render.strategy = RenderStrategy::Modal;
  EXPECT_EQ(choose_model_policy(s, optical_domains(s).domains, no_lens_measurement).plate_model,
            PlateModel::Modal);
  s.render.strategy = RenderStrategy::Auto;
  s.render.single_wavelength_nm = 589.0;
  const ModelPolicy mono = choose_model_policy(s, optical_domains(s).domains, no_lens_measurement);
  EXPECT_EQ(mono.plate_model, PlateModel::Exact);
  EXPECT_TRUE(mono.single_wavelength);
}

TEST(ModelPolicy, AutoLensesArePhysicalOnlyWhenTheMeasuredDifferenceExceedsTheTolerance) {
  Scene s = calcite_figure(8);
  s.optics.lens_model = LensModel::Auto;
  s.render.tolerance_de2000 = 0.5;
  const auto domains = optical_domains(s).domains;
  const ModelPolicy small = choose_model_policy(s, domains, [](const LensPolarizationTable&) { return 0.2; });
  EXPECT_EQ(small.lenses, nullptr);
  ASSERT_TRUE(small.lens_difference_dL);
  EXPECT_EQ(*small.lens_difference_dL, 0.2);
  const ModelPolicy large = choose_model_policy(s, domains, [](const LensPolarizationTable&) { return 0.8; });
  EXPECT_NE(large.lenses, nullptr);
  // The report says which, with the measured ΔL*.
  const PixelView none;
  EXPECT_NE(model_report(small, none).find("ideal (auto: physical differs by ΔL*≈0.20)"), std::string::npos);
  EXPECT_NE(model_report(large, none).find("physical SML lenses (auto: ideal would differ by ΔL*≈0.80)"),
            std::string::npos);
}

TEST(RadialModalTable, AgreesWithDirectFits) {
  const auto plan = compile_evaluation_plan(calcite_figure(16));
  ASSERT_TRUE(plan);
  PreparedPlate anchors[3];
  for (int a = 0; a < 3; ++a) anchors[a] = plan->prepare(0, ModalFit::kAnchorNm[a]);
  RadialModalTable table;
  ASSERT_TRUE(table.build(anchors, 0.85));
  double max_dgamma = 0.0;
  for (double s : {0.05, 0.3, 0.55, 0.8})
    for (double phi : {0.0, 0.7, 2.0, 4.4}) {
      const glm::dvec3 k{s * std::cos(phi), s * std::sin(phi), std::sqrt(1.0 - s * s)};
      ModalFit direct;
      direct.fit(anchors, k);
      const ModalFit interpolated = table.at(k);
      for (int a = 0; a < 3; ++a) {
        max_dgamma =
            std::max(max_dgamma, std::fabs(direct.gamma_at_anchor(a) - interpolated.gamma_at_anchor(a)));
        // Mode directions agree up to sign (a mode is defined up to sign).
        EXPECT_NEAR(std::fabs(glm::dot(direct.e1_at_anchor(a), interpolated.e1_at_anchor(a))), 1.0, 1e-6);
      }
    }
  // Linear interpolation in sin²θ over 1025 entries: ≈ 0.01 nm of Γ for 1 mm calcite at NA 0.85
  // (radial_modal_table.h); 0.05 nm leaves room for the rim, where Γ curves most.
  EXPECT_LT(max_dgamma, 0.05);
}

TEST(Conversions, JonesFromRealReadsGlmColumnMajor) {
  glm::dmat2 m(0.0);
  m[0][0] = 1.0;  // column 0, row 0
  m[1][0] = 2.0;  // column 1, row 0: out.x from in.y
  m[0][1] = 3.0;  // column 0, row 1: out.y from in.x
  m[1][1] = 4.0;
  const JonesMatrix j = jones_from_real(m);
  EXPECT_EQ(j.xx, complexd(1.0));
  EXPECT_EQ(j.xy, complexd(2.0));
  EXPECT_EQ(j.yx, complexd(3.0));
  EXPECT_EQ(j.yy, complexd(4.0));
  const glm::dvec2 v = m * glm::dvec2(5.0, 7.0);
  const JonesVector w = j * JonesVector{5.0, 7.0};
  EXPECT_EQ(w.x.real(), v.x);
  EXPECT_EQ(w.y.real(), v.y);
}

TEST(Conversions, CielabLightnessIsTheLOfXyzToLab) {
  const glm::dvec3 white(0.95047, 1.0, 1.08883);
  for (double y : {0.0, 0.001, 216.0 / 24389.0, 0.01, 0.18, 0.5, 1.0}) {
    EXPECT_EQ(cielab_lightness(y), xyz_to_lab(white * y, white).x) << y;  // one formula: bit-identical
  }
  EXPECT_NEAR(cielab_lightness(1.0), 100.0, 1e-12);
  EXPECT_NEAR(cielab_lightness(0.18), 49.496, 1e-3);  // mid grey, CIE 15:2004 §8.2.1
}
