// Orthoscopic behaviour of plates: extinction, compensator addition and subtraction, the exposure
// reference, stability for degenerate crystals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/render/michel_levy_chart.h"
#include "core/render/progressive_renderer.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

using namespace pmsim;

namespace {

Scene small_scene() {
  Scene s;
  s.render.width = s.render.height = 4;
  return s;
}

glm::dvec3 centre_xyz(const RenderImage& img) {
  const std::size_t i = 3 * (static_cast<std::size_t>(img.height / 2) * img.width + img.width / 2);
  return {img.xyz[i], img.xyz[i + 1], img.xyz[i + 2]};
}

glm::dvec3 lab_of(const glm::dvec3& xyz) { return xyz_to_lab(xyz, illuminant_white_xyz(Illuminant::D65)); }

void expect_all_finite(const RenderImage& img) {
  for (float v : img.rgb) ASSERT_TRUE(std::isfinite(v));
  for (float v : img.xyz) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace

TEST(Exposure, EmptyStageBetweenParallelPolarsIsUniformD65White) {
  Scene s = small_scene();
  s.sample_in = false;
  s.analyzer_deg = 0.0;
  s.render.width = 16;
  s.render.height = 8;
  const RenderImage img = ProgressiveRenderer::render(s, 1);
  expect_all_finite(img);
  const glm::dvec3 white = illuminant_white_xyz(Illuminant::D65);
  for (std::size_t i = 0; i < img.xyz.size(); i += 3) {
    // The band weights integrate the observer exactly, so T ≡ 1 gives the white to rounding.
    EXPECT_NEAR(img.xyz[i + 1], 1.0, 1e-6);
    EXPECT_NEAR(img.xyz[i], white.x, 1e-5);
    EXPECT_NEAR(img.xyz[i + 2], white.z, 1e-5);
  }
}

TEST(Exposure, IsotropicMountingLayerBetweenParallelPolarsGivesYOne) {
  // An isotropic crystal with the mounting medium's index: no birefringence, no Fresnel loss.
  Scene s = small_scene();
  s.analyzer_deg = 0.0;
  s.sample.crystal = CrystalIndices{true, 1.54, 1.54};
  const glm::dvec3 xyz = centre_xyz(ProgressiveRenderer::render(s, 1));
  // Mounting medium n ≈ 1.54 (but dispersive): residual Fresnel loss (Δn ≲ 0.02)² ≈ 1e-4.
  EXPECT_NEAR(xyz.y, 1.0, 1e-3);
}

TEST(Extinction, PlateWithOpticAxisInTheStagePlaneGoesDarkEvery90Degrees) {
  Scene s = small_scene();
  s.sample.mineral = "quartz";
  s.sample.optic_axis = {1, 0, 0};
  s.sample.thickness_um = 30.0;
  for (double stage : {0.0, 90.0, 180.0, 270.0}) {
    s.stage_deg = stage;
    // Vibration directions along the polars: the polarizer's light is one eigenmode and the
    // analyzer blocks it; only the optical activity of quartz (~0.65° over 30 µm, along c only,
    // negligible ⟂ c) could leak: Y < 1e-6.
    EXPECT_LT(centre_xyz(ProgressiveRenderer::render(s, 1)).y, 1e-6) << "stage " << stage;
  }
  for (double stage : {45.0, 135.0, 225.0, 315.0}) {
    s.stage_deg = stage;
    // 45° position: first-order white of Γ ≈ 270 nm, Y ≈ 0.5 (Michel-Lévy).
    EXPECT_GT(centre_xyz(ProgressiveRenderer::render(s, 1)).y, 0.3) << "stage " << stage;
  }
}

TEST(Compensator, GypsumAddsWhenSlowDirectionsAreParallelAndSubtractsWhenCrossed) {
  // Quartz (positive: c is the slow direction), 15 µm: Γ ≈ 136 nm, first-order grey.
  Scene s = small_scene();
  s.sample.mineral = "quartz";
  s.sample.thickness_um = 15.0;
  s.compensator = Compensator::Gypsum;
  s.sample.optic_axis = {std::sqrt(0.5), std::sqrt(0.5), 0.0};  // slow ∥ gypsum slow (NE–SW)
  const glm::dvec3 add = centre_xyz(ProgressiveRenderer::render(s, 1));
  s.sample.optic_axis = {-std::sqrt(0.5), std::sqrt(0.5), 0.0};  // slow ⟂ gypsum slow
  const glm::dvec3 sub = centre_xyz(ProgressiveRenderer::render(s, 1));
  const glm::dvec3 lab_add = lab_of(add), lab_sub = lab_of(sub);
  // Addition: Γ ≈ 550 + 136 ≈ 690 nm, second-order blue (b* strongly negative on the chart).
  EXPECT_LT(lab_add.z, -20.0);
  // Subtraction: Γ ≈ 550 − 136 ≈ 414 nm, first-order yellow (b* strongly positive).
  EXPECT_GT(lab_sub.z, 30.0);
  // And both are the chart colours of those retardations up to the dispersion of gypsum and
  // quartz (which the chart ignores): within 6 CIEDE2000.
  const glm::dvec3 w = illuminant_white_xyz(Illuminant::D65);
  EXPECT_LT(ciede2000(lab_add, xyz_to_lab(michel_levy_xyz(550 + 136, Illuminant::D65), w)), 6.0);
  EXPECT_LT(ciede2000(lab_sub, xyz_to_lab(michel_levy_xyz(550 - 136, Illuminant::D65), w)), 6.0);
}

TEST(Compensator, GypsumAloneShowsFirstOrderRed) {
  Scene s = small_scene();
  s.sample_in = false;
  s.compensator = Compensator::Gypsum;
  const glm::dvec3 lab = lab_of(centre_xyz(ProgressiveRenderer::render(s, 1)));
  // Γ = 550 nm: magenta-red, a* > 0 and b* < 0 on the chart.
  EXPECT_GT(lab.y, 15.0);
  EXPECT_LT(lab.z, 0.0);
}

TEST(Stability, ZeroBirefringenceIsExtinctInEveryPosition) {
  Scene s = small_scene();
  s.sample.crystal = CrystalIndices{true, 1.6, 1.6};
  for (double stage : {0.0, 17.0, 45.0}) {
    s.stage_deg = stage;
    const RenderImage img = ProgressiveRenderer::render(s, 1);
    expect_all_finite(img);
    EXPECT_LT(centre_xyz(img).y, 1e-9) << "stage " << stage;
  }
}

TEST(Stability, SectionsAndWedgesHaveNoNaNOrInf) {
  for (const char* section : {"granite", "basalt"}) {
    Scene s;
    s.sample.type = SampleType::Section;
    s.sample.section = section;
    s.render.width = 48;
    s.render.height = 32;
    s.stage_deg = 33.0;
    for (const bool cono : {false, true}) {
      s.mode = cono ? ViewMode::Cono : ViewMode::Ortho;
      s.bertrand_in = cono;
      const RenderImage img = ProgressiveRenderer::render(s, 1);
      expect_all_finite(img);
      EXPECT_TRUE(img.converged) << section;
    }
  }
  Scene w;
  w.sample.type = SampleType::Wedge;
  w.sample.optic_axis = {1, 1, 0};
  w.sample.thickness_um = 200;
  w.render.width = 64;
  w.render.height = 8;
  const RenderImage img = ProgressiveRenderer::render(w, 1);
  expect_all_finite(img);
  // The wedge starts at zero thickness: the leftmost column (Γ ≈ 14 nm at its centre) is nearly
  // black, Y ≈ (πΓ/λ)² ≈ 0.006–0.01, and the first-order grey brightens to the right while
  // Γ < 250 nm (the first 8 columns: Γ ≤ 225 nm).
  EXPECT_LT(img.xyz[1], 0.02);
  for (int x = 1; x < 8; ++x) EXPECT_GT(img.xyz[3 * x + 1], img.xyz[3 * (x - 1) + 1]) << "column " << x;
}

TEST(Pleochroism, BiotiteChangesColourInPlanePolarizedLightAsTheStageTurns) {
  // Analyzer out: the light vibrating along the polarizer (E–W) samples the absorption of the
  // crystal direction lying E–W. Biotite absorbs strongly for vibrations in the cleavage plane
  // (β, γ: dark brown) and weakly across it (α: pale), so a section ⟂ (001) with the cleavage
  // trace E–W is dark and turns pale at 90° (Nesse 2012, biotite).
  Scene s = small_scene();
  s.analyzer_in = false;
  s.sample.mineral = "biotite";
  s.sample.thickness_um = 30.0;
  s.sample.x_axis = {0, 1, 0};  // α ⟂ cleavage, here N–S at stage 0
  s.sample.z_axis = {1, 0, 0};  // γ in the cleavage plane, E–W
  const glm::dvec3 dark = centre_xyz(ProgressiveRenderer::render(s, 1));
  s.stage_deg = 90.0;
  const glm::dvec3 pale = centre_xyz(ProgressiveRenderer::render(s, 1));
  EXPECT_LT(dark.y, pale.y);
  // A visible change: more than 10 CIEDE2000 between the two positions.
  EXPECT_GT(ciede2000(lab_of(dark), lab_of(pale)), 10.0);
}

// Absorbing (pleochroic) crystals in parallel light are one evaluation for the whole field, so
// `auto` evaluates them with exact Jones matrices per band instead of the three-anchor modal fit,
// whose interpolated absorption left biotite grains of the granite at mean ΔE00 0.7.
TEST(AbsorbingCrystal, AutoUsesExactJonesMatricesInParallelLight) {
  for (const bool analyzer : {false, true}) {
    Scene s = small_scene();
    s.sample.mineral = "biotite";
    s.sample.thickness_um = 30.0;
    s.sample.x_axis = {0, 0, 1};  // nα ⟂ the cleavage (the section normal), as a biotite flake
    s.sample.z_axis = {1, 0, 0};
    s.stage_deg = 30.0;
    s.analyzer_in = analyzer;
    Scene exact = s, modal = s;
    exact.render.strategy = RenderStrategy::Exact;
    modal.render.strategy = RenderStrategy::Modal;
    const RenderImage a = ProgressiveRenderer::render(s, 1);
    const RenderImage e = ProgressiveRenderer::render(exact, 1);
    const RenderImage m = ProgressiveRenderer::render(modal, 1);
    EXPECT_NE(a.model_report.find("absorbing crystals in parallel light"), std::string::npos)
        << a.model_report;
    const double de_auto = ciede2000(lab_of(centre_xyz(a)), lab_of(centre_xyz(e)));
    const double de_modal = ciede2000(lab_of(centre_xyz(m)), lab_of(centre_xyz(e)));
    std::printf("[absorbing] biotite 30 µm, analyzer %s: auto %.3f, modal %.3f ΔE00 from exact\n",
                analyzer ? "in" : "out", de_auto, de_modal);
    // Both exact and converged to the scene tolerance (0.5 by default, estimated between levels):
    // well inside 0.5 of each other.
    EXPECT_LT(de_auto, 0.5);
  }
}
