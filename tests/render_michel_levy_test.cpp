// Orthoscopic interference colours against an independent computation: a non-dispersive plate at
// 45° between crossed polars transmits T(λ) = sin²(πΓ/λ) (Born & Wolf §15.4.2), parallel polars
// cos²(πΓ/λ); the colour is ∫T·S·(x̄,ȳ,z̄)dλ / ∫S·ȳ dλ. The reference here is a plain 0.05 nm
// midpoint sum of that integral — it shares no code with the renderer's band integration.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/units.h"
#include "core/render/michel_levy_chart.h"
#include "core/render/progressive_renderer.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

using namespace pmsim;

namespace {

glm::dvec3 reference_xyz(double gamma_nm, bool parallel) {
  glm::dvec3 xyz(0.0);
  const double step = 0.05;
  for (double l = 380.0 + 0.5 * step; l < 780.0; l += step) {
    const double s = std::sin(kPi * gamma_nm / l);
    xyz += observer_weight(Illuminant::D65, l) * (parallel ? 1.0 - s * s : s * s) * step;
  }
  return xyz;
}

double de(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 w = illuminant_white_xyz(Illuminant::D65);
  return ciede2000(xyz_to_lab(a, w), xyz_to_lab(b, w));
}

// Non-dispersive uniaxial crystal, indices close to the mounting medium (Fresnel losses at the
// faces < 1e-5), optic axis in the stage plane at 45° to the polars.
Scene plate_scene(double gamma_nm) {
  Scene s;
  s.sample.crystal = CrystalIndices{true, 1.540, 1.550};
  s.sample.optic_axis = {std::sqrt(0.5), std::sqrt(0.5), 0.0};
  s.sample.thickness_um = std::max(1e-3, gamma_nm / 0.010 * 1e-3);
  s.render.width = s.render.height = 4;
  return s;
}

glm::dvec3 centre_xyz(const RenderImage& img) {
  const std::size_t i = 3 * (static_cast<std::size_t>(img.height / 2) * img.width + img.width / 2);
  return {img.xyz[i], img.xyz[i + 1], img.xyz[i + 2]};
}

}  // namespace

TEST(MichelLevy, PlateAt45BetweenCrossedPolarsMatchesSinSquaredIntegral) {
  for (double gamma = 0.0; gamma <= 2000.0; gamma += 50.0) {
    const RenderImage img = ProgressiveRenderer::render(plate_scene(gamma), 1);
    ASSERT_TRUE(img.converged);
    const glm::dvec3 got = centre_xyz(img), want = reference_xyz(gamma, false);
    // Issue tolerance: CIEDE2000 ≤ 1 (a just-noticeable difference). At Γ = 0 both are black.
    EXPECT_LE(de(got, want), 1.0) << "Γ = " << gamma << " nm";
  }
}

TEST(MichelLevy, ParallelPolarsGiveTheComplementaryColour) {
  for (double gamma = 100.0; gamma <= 2000.0; gamma += 150.0) {
    Scene s = plate_scene(gamma);
    s.analyzer_deg = 0.0;
    const glm::dvec3 par = centre_xyz(ProgressiveRenderer::render(s, 1));
    s.analyzer_deg = 90.0;
    const glm::dvec3 crossed = centre_xyz(ProgressiveRenderer::render(s, 1));
    EXPECT_LE(de(par, reference_xyz(gamma, true)), 1.0) << "Γ = " << gamma;
    // sin² + cos² = 1: crossed + parallel is the white of the exposure reference (Y = 1), up to
    // the plate's Fresnel loss (< 1e-4 here) and the convergence tolerance.
    const glm::dvec3 white = illuminant_white_xyz(Illuminant::D65);
    EXPECT_NEAR(par.y + crossed.y, 1.0, 2e-3) << "Γ = " << gamma;
    EXPECT_LE(de(par + crossed, white), 0.5) << "Γ = " << gamma;
  }
}

TEST(MichelLevy, ChartColumnsAreTheInterferenceColours) {
  const int w = 41;
  const std::vector<float> chart = michel_levy_chart(w, 2, 2000.0, Illuminant::D65);
  ASSERT_EQ(chart.size(), static_cast<std::size_t>(w) * 2 * 3);
  for (int x = 0; x < w; ++x) {
    const double gamma = 2000.0 * (x + 0.5) / w;
    const std::size_t i = 3 * static_cast<std::size_t>(w + x);  // second row
    const glm::dvec3 rgb(chart[i], chart[i + 1], chart[i + 2]);
    EXPECT_LE(de(linear_srgb_to_xyz(rgb), reference_xyz(gamma, false)), 1.0) << "Γ = " << gamma;
  }
}

TEST(MichelLevy, HighOrderPlateAveragesToWhiteWithoutAliasing) {
  // 10 mm of quartz at 45°: Γ ≈ 90 µm, ~160 orders. Averaged over any band of the spectrum the
  // sin² term is 1/2: the colour must be "high-order white", Y = 1/2, neutral.
  Scene s;
  s.sample.mineral = "quartz";
  s.sample.optic_axis = {std::sqrt(0.5), std::sqrt(0.5), 0.0};
  s.sample.thickness_um = 10000.0;
  s.render.width = s.render.height = 4;
  const RenderImage img = ProgressiveRenderer::render(s, 1);
  const glm::dvec3 xyz = centre_xyz(img);
  ASSERT_TRUE(std::isfinite(xyz.x + xyz.y + xyz.z));
  // Residual of the band average at ~160 orders is ≪ 1 %; 0.01 leaves room for Fresnel losses.
  EXPECT_NEAR(xyz.y, 0.5, 0.01);
  const glm::dvec3 lab = xyz_to_lab(xyz, illuminant_white_xyz(Illuminant::D65));
  // Neutral: chroma below 2 CIELAB units (invisible next to the first-order colours, C* > 20).
  EXPECT_LT(std::hypot(lab.y, lab.z), 2.0);
}

TEST(MichelLevyChart, BirefringenceLinesFollowRetardationEqualsThicknessTimesBirefringence) {
  const double max_nm = 1800.0, max_um = 50.0;
  const auto lines = michel_levy_lines(max_nm, max_um);
  ASSERT_EQ(lines.size(), michel_levy_standard_birefringences().size());
  for (const MichelLevyLine& l : lines) {
    SCOPED_TRACE(l.label);
    // Γ[nm] = 1000·d[µm]·Δn (the definition of retardation); 1e-9 relative: rounding only.
    EXPECT_NEAR(l.to.x, 1000.0 * l.to.y * l.birefringence, 1e-9 * l.to.x);
    // The line ends on the chart's top edge (d = 50 µm) or, for large Δn, on its right edge.
    if (l.ends_on_top) {
      EXPECT_DOUBLE_EQ(l.to.y, max_um);
      EXPECT_LE(l.to.x, max_nm);
    } else {
      EXPECT_DOUBLE_EQ(l.to.x, max_nm);
      EXPECT_LT(l.to.y, max_um);
    }
    EXPECT_EQ(std::stod(l.label), l.birefringence);
  }
  // Quartz (Δn 0.009) in a 30 µm section shows first-order white-yellow Γ ≈ 270 nm; 0.010 ends at
  // Γ = 500 nm on the top edge, calcite's 0.172 is far off the top (right edge at d ≈ 10.5 µm).
  const auto q = michel_levy_lines(max_nm, max_um, {0.010, 0.172});
  EXPECT_TRUE(q[0].ends_on_top);
  EXPECT_NEAR(q[0].to.x, 500.0, 1e-9);
  EXPECT_FALSE(q[1].ends_on_top);
  EXPECT_NEAR(q[1].to.y, 1800.0 / 172.0, 1e-9);
  // Drawn: the pixel on the Δn = 0.010 line at d = 25 µm (Γ = 250 nm) is darker than the plain
  // chart's; a pixel far from every line is unchanged.
  const int w = 360, h = 100;
  const auto plain = michel_levy_chart(w, h, max_nm);
  const auto drawn = michel_levy_chart_with_lines(w, h, max_nm, max_um, Illuminant::D65, {0.010});
  const int x = static_cast<int>(250.0 / max_nm * w), y = static_cast<int>((1.0 - 25.0 / max_um) * h);
  const std::size_t on = (static_cast<std::size_t>(y) * w + x) * 3 + 1;
  EXPECT_LT(drawn[on], 0.5f * plain[on]);
  const std::size_t off = (static_cast<std::size_t>(10) * w + 300) * 3 + 1;
  EXPECT_EQ(drawn[off], plain[off]);
}
