// The renderer (core/render) on the hard scenes: a cone lit to NA 0.99 (rays within 8° of
// grazing in the mount), a view straight down an optic axis, zero birefringence, a 58 mm plate
// (Γ = 1e7 nm: thousands of orders must average to high-order white, not alias), an empty stage.
// Images must be finite, bounded, and physically right where the answer is known.
#include <cmath>

#include <gtest/gtest.h>

#include "core/io/scene_file.h"
#include "core/render/progressive_renderer.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "tests/asset_scene.h"

namespace pmsim {
namespace {

Scene small(ViewMode mode) {
  Scene s;
  s.mode = mode;
  s.bertrand_in = mode == ViewMode::Cono;
  s.render.width = s.render.height = 24;
  s.optics.lens_model = LensModel::Ideal;
  return s;
}

struct Stats {
  double min_y = 1e300, max_y = -1e300, mean_y = 0.0, max_chroma = 0.0;
  bool finite = true;
};

Stats stats(const RenderImage& img, Illuminant illum) {
  Stats st;
  const glm::dvec3 white = illuminant_white_xyz(illum);
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 xyz(img.xyz[3 * i], img.xyz[3 * i + 1], img.xyz[3 * i + 2]);
    for (int c = 0; c < 3; ++c)
      st.finite = st.finite && std::isfinite(img.xyz[3 * i + c]) && std::isfinite(img.rgb[3 * i + c]);
    st.min_y = std::min(st.min_y, xyz.y);
    st.max_y = std::max(st.max_y, xyz.y);
    st.mean_y += xyz.y / n;
    const glm::dvec3 lab = xyz_to_lab(xyz, white);
    st.max_chroma = std::max(st.max_chroma, std::hypot(lab.y, lab.z));
  }
  return st;
}

TEST(StabilityRender, HardScenesGiveFiniteBoundedImages) {
  std::vector<std::pair<const char*, Scene>> scenes;
  {
    Scene s = asset_scene("calcite_cono.json");  // calcite 1 mm ⟂ c
    s.render.width = s.render.height = 24;
    s.optics.lens_model = LensModel::Ideal;
    s.objective.na = 0.99;
    s.condenser.na = 0.99;
    scenes.push_back({"calcite cone to NA 0.99", s});
  }
  {
    Scene s = small(ViewMode::Cono);
    s.sample.mineral = "muscovite";
    s.sample.thickness_um = 40.0;
    s.sample.x_axis = {0, 0, 1};
    s.sample.z_axis = {1, 0, 0};
    scenes.push_back({"muscovite Bxa (binormals in the field)", s});
  }
  {
    Scene s = small(ViewMode::Ortho);
    s.sample.mineral = "quartz";
    s.sample.optic_axis = {0, 0, 1};
    s.sample.thickness_um = 1000.0;
    scenes.push_back({"quartz 1 mm along its optic axis (optical activity)", s});
  }
  {
    Scene s = small(ViewMode::Cono);
    s.sample.crystal = CrystalIndices{true, 1.55, 1.55};
    scenes.push_back({"zero birefringence, cono", s});
  }
  for (auto& [name, s] : scenes)
    for (bool analyzer : {true, false}) {
      s.analyzer_in = analyzer;
      const RenderImage img = ProgressiveRenderer::render(s, 2);
      const Stats st = stats(img, s.illuminant);
      ASSERT_TRUE(st.finite) << name;
      // Passive optics: no pixel brighter than the exposure reference Y = 1 (+1 % for the
      // band quadrature of the weights) and none negative beyond the rounding of the modal sum
      // C0 + Cφ·cos φ + … of O(1) terms that cancel on a dark isogyre (1e-12).
      EXPECT_GE(st.min_y, -1e-12) << name;
      EXPECT_LE(st.max_y, 1.01) << name;
    }
}

TEST(StabilityRender, ZeroBirefringenceIsDarkBetweenCrossedPolars) {
  for (double dn : {0.0, 1e-12}) {
    Scene s = small(ViewMode::Ortho);
    s.sample.crystal = CrystalIndices{true, 1.55, 1.55 + dn};
    s.sample.optic_axis = {1, 0, 0};
    s.stage_deg = 45.0;
    const Stats st = stats(ProgressiveRenderer::render(s, 2), s.illuminant);
    ASSERT_TRUE(st.finite);
    // Γ = 30 µm·1e-12 = 3e-8 nm: Y = sin²(πΓ/λ) ~ 3e-20; allow 1e-12.
    EXPECT_LT(st.max_y, 1e-12) << dn;
  }
}

TEST(StabilityRender, TenMillionNanometreRetardationAveragesToHighOrderWhite) {
  // Calcite-like constant indices, optic axis in the stage plane at 45°: Γ = d·Δn ≈ 1e7 nm
  // (58 mm). Between crossed polars the Michel-Lévy colour of ~2e4 orders is white of half the
  // intensity: Y = ½·∫T_fresnel ≈ 0.5 × the two faces' transmission (> 0.9), chroma near 0.
  Scene s = small(ViewMode::Ortho);
  s.sample.crystal = CrystalIndices{true, 1.658, 1.486};
  s.sample.optic_axis = {1, 0, 0};
  s.sample.thickness_um = 1e7 / 0.172 / 1000.0;
  s.stage_deg = 45.0;
  const Stats st = stats(ProgressiveRenderer::render(s, 2), s.illuminant);
  ASSERT_TRUE(st.finite);
  EXPECT_NEAR(st.mean_y, 0.5, 0.05);     // ½ minus < 10 % Fresnel loss at the two faces
  EXPECT_LT(st.max_y - st.min_y, 1e-6);  // a uniform plate: one evaluation for the field
  // Aliasing would leave a random colour of a few orders (chroma 20–60); high-order white has a
  // chroma of a few units at most (the residual oscillation averages over 400 nm / 2e4 orders).
  EXPECT_LT(st.max_chroma, 3.0);
}

TEST(StabilityRender, EmptyStageBetweenParallelPolarsIsUniformWhite) {
  for (ViewMode mode : {ViewMode::Ortho, ViewMode::Cono}) {
    Scene s = small(mode);
    s.sample_in = false;
    s.analyzer_deg = 0.0;
    const RenderImage img = ProgressiveRenderer::render(s, 2);
    const Stats st = stats(img, s.illuminant);
    ASSERT_TRUE(st.finite);
    // The exposure convention: Y = 1 exactly where lit (outside the conoscopic disk: 0).
    EXPECT_NEAR(st.max_y, 1.0, 1e-6);
    if (mode == ViewMode::Ortho) {
      EXPECT_NEAR(st.min_y, 1.0, 1e-6);
    }
  }
}

}  // namespace
}  // namespace pmsim
