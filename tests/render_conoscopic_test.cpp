// Conoscopic figures against closed-form plane-wave optics. The figure maps back-focal-plane
// radius ρ to sin θ_air = ρ·NA (the convention).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/base/units.h"
#include "core/render/progressive_renderer.h"
#include "tests/asset_scene.h"

using namespace pmsim;

namespace {

constexpr int kSize = 512;

Scene cono_scene() {
  Scene s;
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  s.objective.na = 0.85;
  s.condenser.na = 0.9;
  s.render.width = s.render.height = kSize;
  // Closed-form plane-wave optics assume perfect lenses; the physical lens model is tested below.
  s.optics.lens_model = LensModel::Ideal;
  return s;
}

double Y(const RenderImage& img, int x, int y) {
  return img.xyz[3 * (static_cast<std::size_t>(y) * img.width + x) + 1];
}

// Intensity profile along the image diagonal from the centre toward NE: (ρ, Y) at pixel centres.
std::vector<std::pair<double, double>> diagonal_profile(const RenderImage& img, bool north_west = false) {
  std::vector<std::pair<double, double>> p;
  const int c = img.width / 2;
  for (int i = 0; c + i < img.width && c - 1 - i >= 0; ++i) {
    const int x = north_west ? c - 1 - i : c + i, y = c - 1 - i;
    const double rho = std::sqrt(2.0) * (i + 0.5) / c;
    if (rho > 1.0) break;
    p.push_back({rho, Y(img, x, y)});
  }
  return p;
}

// Local minima refined by a parabola through three samples (positions in ρ).
std::vector<double> minima(const std::vector<std::pair<double, double>>& p) {
  std::vector<double> m;
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const double a = p[i - 1].second, b = p[i].second, c = p[i + 1].second;
    if (b < a && b <= c) {
      const double denom = a - 2 * b + c;
      const double off = denom > 0 ? 0.5 * (a - c) / denom : 0.0;
      m.push_back(p[i].first + off * (p[i + 1].first - p[i].first));
    }
  }
  return m;
}

double bisect(const std::function<double(double)>& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((f(lo) < 0) == (f(mid) < 0) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(ConoscopicUniaxial, DarkIsochromeRadiiMatchTheExactPlaneWaveRetardation) {
  // Calcite (constant indices at 589 nm, Ghosh 1999: no 1.6584, ne 1.4864), 40 µm ⟂ c.
  const double no = 1.6584, ne = 1.4864, d_nm = 40000.0, lambda = 589.0;
  Scene s = cono_scene();
  s.sample.crystal = CrystalIndices{true, no, ne};
  s.sample.optic_axis = {0, 0, 1};
  s.sample.thickness_um = d_nm * 1e-3;
  s.render.single_wavelength_nm = lambda;
  const RenderImage img = ProgressiveRenderer::render(s, 2);
  // Exact plane-wave retardation for tangential wave-vector s = sin θ_air (optic axis ∥ z):
  // k_z,o = √(no² − s²), k_z,e = (no/ne)·√(ne² − s²) (Born & Wolf §15.3; Yariv & Yeh §4.3);
  // Γ = d·|k_z,o − k_z,e|. Dark rings at Γ = mλ.
  auto gamma = [&](double sn) {
    return d_nm * std::fabs(std::sqrt(no * no - sn * sn) - no / ne * std::sqrt(ne * ne - sn * sn));
  };
  const std::vector<double> found = minima(diagonal_profile(img));
  int checked = 0;
  for (int m = 1; m <= 4; ++m) {
    if (gamma(s.objective.na * 0.99) < m * lambda) break;
    const double s_m = bisect([&](double sn) { return gamma(sn) - m * lambda; }, 1e-6, s.objective.na * 0.99);
    const double rho_m = s_m / s.objective.na;
    double best = 1e9;
    for (double r : found)
      if (std::fabs(r - rho_m) < std::fabs(best - rho_m)) best = r;
    // Issue tolerance 0.5 %; the parabolic sub-pixel fit locates a minimum to ≲0.2 px of the
    // ~100–230 px radii here.
    EXPECT_NEAR(best, rho_m, 0.005 * rho_m) << "ring m = " << m;
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

TEST(ConoscopicUniaxial, IsogyresFollowThePolarsNotTheStage) {
  Scene s = cono_scene();
  s.render.width = s.render.height = 128;
  s.sample.mineral = "calcite";
  s.sample.optic_axis = {0, 0, 1};
  s.sample.thickness_um = 100.0;
  const int c = 64, r = 40;  // sample points at radius 40 px
  auto at_angle = [&](const RenderImage& img, double deg) {
    const double a = radians(deg);
    return Y(img, c + static_cast<int>(std::lround(r * std::cos(a))),
             c - 1 - static_cast<int>(std::lround(r * std::sin(a))));
  };
  for (double stage : {0.0, 30.0}) {
    s.stage_deg = stage;
    s.polarizer_deg = 0;
    s.analyzer_deg = 90;
    const RenderImage img = ProgressiveRenderer::render(s, 2);
    // Along the polarizer (0°) and analyzer (90°) vibration directions: dark; at 45°: bright.
    EXPECT_LT(at_angle(img, 0.0), 0.02) << "stage " << stage;
    EXPECT_LT(at_angle(img, 90.0), 0.02) << "stage " << stage;
    EXPECT_GT(at_angle(img, 45.0), 0.1) << "stage " << stage;
  }
  s.stage_deg = 0;
  s.polarizer_deg = 30;
  s.analyzer_deg = 120;
  const RenderImage turned = ProgressiveRenderer::render(s, 2);
  // Turning the polars by 30° turns the cross with them.
  EXPECT_LT(at_angle(turned, 30.0), 0.02);
  EXPECT_LT(at_angle(turned, 120.0), 0.02);
  EXPECT_GT(at_angle(turned, 0.0), 0.05);
}

TEST(ConoscopicBiaxial, MelatopesLieAtSinEEqualsNBetaSinV) {
  const double na = 1.60, nb = 1.61, ng = 1.64;
  // 2Vz from the indices (Born & Wolf §15.3.3): cos²Vz = nα²(nγ² − nβ²) / (nβ²(nγ² − nα²)).
  const double cos2v = na * na * (ng * ng - nb * nb) / (nb * nb * (ng * ng - na * na));
  const double V = std::acos(std::sqrt(cos2v));
  const double sinE = nb * std::sin(V);
  Scene s = cono_scene();
  s.objective.na = 0.95;
  s.condenser.na = 0.95;
  s.sample.crystal = CrystalIndices{false, 1.5, 1.5, 1.5};
  s.sample.crystal->nalpha = na;
  s.sample.crystal->nbeta = nb;
  s.sample.crystal->ngamma = ng;
  s.sample.x_axis = {1, 0, 0};
  s.sample.z_axis = {0, 0, 1};
  s.sample.thickness_um = 40.0;  // Γ(centre) = d(nβ − nα) = 400 nm < λ: the melatope is the only zero
  s.render.single_wavelength_nm = 589.0;
  s.stage_deg = 45.0;  // optic-axial plane NE–SW
  const RenderImage img = ProgressiveRenderer::render(s, 2);
  const double rho_expected = sinE / s.objective.na;
  const std::vector<double> found = minima(diagonal_profile(img));
  ASSERT_FALSE(found.empty());
  double best = found.front();
  for (double r : found)
    if (std::fabs(r - rho_expected) < std::fabs(best - rho_expected)) best = r;
  // One pixel of the 256-px radius ≈ 0.4 % of ρ ≈ 0.86; allow 1 %.
  EXPECT_NEAR(best, rho_expected, 0.01 * rho_expected);
  // The optic-axial plane is NE–SW: along the NW diagonal there is no zero of Γ inside the disk.
  for (double r : minima(diagonal_profile(img, true))) EXPECT_GT(std::fabs(r - rho_expected), 0.05);
}

TEST(ConoscopicBiaxial, AcuteBisectrixCrossOpensIntoHyperbolaeAt45Degrees) {
  Scene s = cono_scene();
  s.render.width = s.render.height = 128;
  s.sample.crystal = CrystalIndices{false, 1.5, 1.5, 1.5};
  s.sample.crystal->nalpha = 1.60;
  s.sample.crystal->nbeta = 1.61;
  s.sample.crystal->ngamma = 1.64;
  s.sample.x_axis = {1, 0, 0};
  s.sample.z_axis = {0, 0, 1};
  s.sample.thickness_um = 40.0;
  s.render.single_wavelength_nm = 589.0;
  const int c = 64;
  s.stage_deg = 0.0;
  const RenderImage cross = ProgressiveRenderer::render(s, 2);
  // Extinction position: the centre lies on both arms of the cross (vibrations ∥ polars).
  EXPECT_LT(Y(cross, c, c), 0.01);
  s.stage_deg = 45.0;
  const RenderImage hyper = ProgressiveRenderer::render(s, 2);
  // 45°: the centre's vibrations are at 45° to the polars: sin²(πΓ/λ), Γ = 400 nm → ≈ 0.72; the
  // isogyres have moved out to the melatopes.
  EXPECT_GT(Y(hyper, c, c), 0.3);
}

TEST(ConoscopicStability, RayAlongTheOpticAxisAndGrazingConeStayFinite) {
  Scene s = asset_scene("calcite_cono.json");  // calcite 1 mm ⟂ c
  s.optics.lens_model = LensModel::Ideal;
  s.render.width = s.render.height = 65;  // odd: one pixel exactly on the axis
  s.objective.na = 0.99;
  s.condenser.na = 0.99;
  const RenderImage img = ProgressiveRenderer::render(s, 2);
  for (float v : img.rgb) ASSERT_TRUE(std::isfinite(v));
  // Along the optic axis Γ = 0 and both polars block: the melatope is black.
  EXPECT_LT(Y(img, 32, 32), 1e-6);
  // Outside the disk: black.
  EXPECT_EQ(Y(img, 0, 0), 0.0);
}

TEST(ConoscopicStability, TenMillimetrePlateShowsNoAliasingPattern) {
  // 10 mm quartz, optic axis in the stage plane at 45°: thousands of orders everywhere; adjacent
  // pixels must not differ by more than the retardation gradient allows (high-order white).
  Scene s = cono_scene();
  s.render.width = s.render.height = 64;
  s.objective.na = 0.25;
  s.condenser.na = 0.3;
  s.sample.mineral = "calcite";
  s.sample.optic_axis = {std::sqrt(0.5), std::sqrt(0.5), 0.0};
  s.sample.thickness_um = 10000.0;
  const RenderImage img = ProgressiveRenderer::render(s, 2);
  double ymin = 1e9, ymax = -1e9;
  for (int y = 16; y < 48; ++y)
    for (int x = 16; x < 48; ++x) {
      ymin = std::min(ymin, Y(img, x, y));
      ymax = std::max(ymax, Y(img, x, y));
    }
  // Γ ≈ 1.7 mm (~3000 orders): every pixel averages to Y = 1/2 within 2 %, no moiré.
  EXPECT_GT(ymin, 0.48);
  EXPECT_LT(ymax, 0.52);
}

TEST(PhysicalLenses, OpticalLensesAloneLeakLightInTheDiagonalsOfCrossedPolars) {
  // Empty stage, crossed polars: ideal lenses give a black field. Real lenses transmit s and p
  // differently at oblique incidence (Fresnel), which rotates the polarization of rays in the
  // diagonal azimuths: light leaks there, growing with sin θ, while rays in the polarizer and
  // analyzer azimuths (pure s or p) stay extinct — the lenses' own faint cross.
  Scene s = cono_scene();
  s.render.width = s.render.height = 128;
  s.sample_in = false;
  s.optics.lens_model = LensModel::Ideal;
  const RenderImage ideal = ProgressiveRenderer::render(s, 2);
  s.optics.lens_model = LensModel::Physical;
  const RenderImage phys = ProgressiveRenderer::render(s, 2);
  EXPECT_NE(phys.model_report.find("physical"), std::string::npos);
  const int c = 64;
  auto diag = [&](const RenderImage& img, int r) { return Y(img, c + r, c - 1 - r); };
  for (int r : {10, 30, 40}) EXPECT_LT(diag(ideal, r), 1e-9);
  // Leak ∝ (τp² − τs²)²/4: zero on axis, ~1e-3 near sin θ ≈ 0.8 for glass n ≈ 1.52.
  EXPECT_GT(diag(phys, 40), diag(phys, 10));
  EXPECT_GT(diag(phys, 40), 1e-4);
  EXPECT_LT(diag(phys, 40), 0.05);
  // Along the polarizer azimuth: extinct but for the half-pixel azimuth offset of the pixel
  // centre (0.5/40 rad → sin²(2φ) ≈ 6e-4 of the diagonal leak).
  EXPECT_LT(Y(phys, c + 40, c), 0.01 * diag(phys, 40));
  EXPECT_LT(Y(phys, c, c), 1e-9);
}

TEST(PhysicalLenses, AutoKeepsIdealLensesInParallelLight) {
  Scene s;
  s.render.width = s.render.height = 8;
  const RenderImage img = ProgressiveRenderer::render(s, 1);
  EXPECT_NE(img.model_report.find("objective: ideal"), std::string::npos) << img.model_report;
}
