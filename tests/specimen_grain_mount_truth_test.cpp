// The ground truth of a grain mount (core/specimen/grain_mount_truth.h) against geometry and the
// indicatrix: labels turn with the stage, each fragment's n′ along the polarizer lies between its
// two vibration indices for vertical light, a uniaxial fragment always offers n_ω as one of them,
// and the relief follows n′ against the liquid's n_D.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/crystal/crystal.h"
#include "core/specimen/becke_probe.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/grain_mount_truth.h"

namespace {

pmsim::Scene mount_scene(double stage_deg, double polarizer_deg = 0.0) {
  pmsim::Scene s;
  s.sample.type = pmsim::SampleType::Grains;
  s.sample.mineral = "calcite";
  s.sample.medium_index = 1.54;
  s.render.width = s.render.height = 48;
  s.stage_deg = stage_deg;
  s.polarizer_deg = polarizer_deg;
  return s;
}

}  // namespace

// Turning the stage by 90° turns the image by 90° counter-clockwise (docs/conventions.md): on a
// square grid of an even size the pixel centres map onto each other exactly, so every label must
// reappear at the turned pixel — no tolerance.
TEST(GrainMountTruth, LabelsTurnWithTheStage) {
  const pmsim::Scene s0 = mount_scene(0.0), s90 = mount_scene(90.0);
  const auto mount = pmsim::grain_mount_specimen(s0);
  const std::vector<std::uint16_t> l0 = pmsim::fragment_label_image(*mount, s0);
  const std::vector<std::uint16_t> l90 = pmsim::fragment_label_image(*mount, s90);
  const int n = s0.render.width;
  std::set<std::uint16_t> seen(l0.begin(), l0.end());
  ASSERT_GE(seen.size(), 4u) << "the field shows liquid and several fragments";
  int mismatches = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      // A point at image offset (u, v) (x right, y up) moves to (−v, u) when turned by +90°:
      // pixel (x, y), y down, to (y, n − 1 − x).
      const int xr = y, yr = n - 1 - x;
      mismatches += l90[std::size_t(yr) * n + xr] != l0[std::size_t(y) * n + x];
    }
  EXPECT_EQ(mismatches, 0);
}

TEST(GrainMountTruth, IndicesFollowTheIndicatrixAndTheReliefTheLiquid) {
  const pmsim::Scene s = mount_scene(30.0, 20.0);
  const auto mount = pmsim::grain_mount_specimen(s);
  const std::vector<std::uint16_t> labels = pmsim::fragment_label_image(*mount, s);
  const std::vector<pmsim::FragmentTruth> truths = pmsim::fragment_truths(*mount, s, labels);
  ASSERT_GE(truths.size(), 3u);
  const glm::dvec3 n = pmsim::find_mineral("calcite").principal_indices(pmsim::kBeckeWavelengthNm);
  const double n_e = std::min({n.x, n.y, n.z}), n_o = std::max({n.x, n.y, n.z});
  long long area = 0;
  for (const pmsim::FragmentTruth& t : truths) {
    SCOPED_TRACE(t.label);
    area += t.area_px;
    EXPECT_EQ(t.mineral, "calcite");
    EXPECT_EQ(t.area_px, std::count(labels.begin(), labels.end(), std::uint16_t(t.label)));
    // The optic axes are an orthonormal frame (a rotation of the crystal): 1e-12 is double
    // rounding over a few products.
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(glm::dot(t.optic_axes[i], t.optic_axes[j]), i == j ? 1.0 : 0.0, 1e-12);
    // The radius of the section's ellipse along any direction lies between its semi-axes;
    // 1e-12: rounding of the two index formulas.
    EXPECT_LE(t.n_fast, t.n_polarizer + 1e-12);
    EXPECT_LE(t.n_polarizer, t.n_slow + 1e-12);
    // Calcite is uniaxial negative: the ordinary wave vibrates ⟂ c in every section, so n_slow is
    // n_ω, and n_fast lies between n_ε and n_ω (1e-12 as above).
    EXPECT_NEAR(t.n_slow, n_o, 1e-12);
    EXPECT_GE(t.n_fast, n_e - 1e-12);
    EXPECT_DOUBLE_EQ(t.liquid_n_d, 1.54);
    const double d = t.n_polarizer - 1.54;
    EXPECT_EQ(t.relief_vs_medium, std::abs(d) < pmsim::kBeckeMatch ? "matched" : d > 0 ? "higher" : "lower");
  }
  EXPECT_EQ(area, std::count_if(labels.begin(), labels.end(), [](std::uint16_t l) { return l != 0; }));
  // What the teaching panel's probe says at a fragment's pixel is the same fragment and the same n′.
  const int w = s.render.width;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] == 0) continue;
    const pmsim::BeckeProbe p =
        pmsim::probe_becke_line(*mount, s, (double(i % w) + 0.5) / w, (double(i / w) + 0.5) / s.render.height);
    ASSERT_TRUE(p.on_fragment);
    EXPECT_EQ(p.fragment + 1, labels[i]);
    const auto t = std::find_if(truths.begin(), truths.end(), [&](const auto& f) { return f.label == labels[i]; });
    ASSERT_NE(t, truths.end());
    EXPECT_DOUBLE_EQ(p.mineral_n, t->n_polarizer);
    break;
  }
}
