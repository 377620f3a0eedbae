// The teaching panel's Becke-line probe (core/specimen/becke_probe.h) against the physics: the
// direction it reports on focusing up is the side of the higher index, and it is the side the
// traced image's bright fringe actually moves to (an n = 1.60 fragment in liquids of 1.54 and
// 1.66, rendered at focus +20 µm); for an anisotropic fragment the index is the indicatrix's along
// the polarizer, turned with the stage.
#include <gtest/gtest.h>

#include <cmath>

#include "core/specimen/becke_probe.h"
#include "core/specimen/grain_mount_render.h"
#include "tests/specimen_fixture.h"

using namespace specimen_test;

namespace {

constexpr double kLambdaD = 589.26;

// A scene whose view is the fixture's: 160 px of 1 µm at the stage centre (plane_light_options
// maps the probe's image fractions through the scene's field of view; only its um_per_px and
// size matter here, so the field is set through the render size and read back).
pmsim::Scene probe_scene(double polarizer_deg = 0.0, double stage_deg = 0.0) {
  pmsim::Scene s;
  s.sample.type = pmsim::SampleType::Grains;
  s.render.width = s.render.height = 160;
  s.polarizer_deg = polarizer_deg;
  s.stage_deg = stage_deg;
  return s;
}

// The fraction of the image (from the left) of a point `dx_um` east of the centre.
double x_fraction(const pmsim::Scene& s, double dx_um) {
  const pmsim::PlaneLightOptions o = pmsim::plane_light_options(s);
  return 0.5 + dx_um / (o.width * o.um_per_px);
}

// Which side of the outline the bright fringe lies on at focus +20 µm: +1 inside (it moved into
// the fragment), −1 outside — the side of the brightest 2 µm band within 14 µm of the outline,
// as tests/specimen_becke_line_test.cpp measures it.
int traced_fringe_side(double n_liquid) {
  OneFragment f;
  f.n_liquid = n_liquid;
  const auto s = make_specimen(f);
  const auto o = mono_view(20.0, 32);
  const auto img = pmsim::render_plane_light(*s, o);
  const auto d = signed_distance(*s, o);
  double peak = 0.0, peak_side = 0.0;
  for (double a = -14; a < 14; a += 2) {
    const double m = band_mean(img, d, a, a + 2);
    if (m > peak) peak = m, peak_side = a + 1;
  }
  std::printf("n_liquid %.2f focus +20 µm: brightest band %.3f at %+.0f µm from the outline\n", n_liquid, peak,
              peak_side);
  return peak_side > 0 ? 1 : -1;
}

}  // namespace

TEST(BeckeProbe, IsotropicFragmentReportsTheSideOfTheHigherIndexAsTheTracedImageShowsIt) {
  for (const double n_liquid : {1.54, 1.66}) {
    OneFragment f;
    f.n_liquid = n_liquid;
    const auto specimen = make_specimen(f);
    const pmsim::Scene scene = probe_scene();
    const pmsim::BeckeProbe on = pmsim::probe_becke_line(*specimen, scene, 0.5, 0.5);
    ASSERT_TRUE(on.on_fragment) << "the image centre is the 100 µm fragment's centre";
    EXPECT_EQ(on.fragment, 0);
    // The fixture's fragment has a constant n = 1.60 (no dispersion): exact.
    EXPECT_DOUBLE_EQ(on.mineral_n, 1.60);
    // The liquid's index at 589.26 nm is its n_D by construction of the series (to rounding).
    EXPECT_NEAR(on.liquid_n, pmsim::immersion_liquid(n_liquid).n(kLambdaD), 1e-12);
    EXPECT_NEAR(on.liquid_n, n_liquid, 1e-4);
    const int expected = n_liquid < 1.60 ? 1 : -1;
    EXPECT_EQ(on.moves_into_mineral, expected) << "n_liquid " << n_liquid;
    // The physics the probe claims: focused up, the bright fringe lies on that side.
    EXPECT_EQ(traced_fringe_side(n_liquid), expected) << "n_liquid " << n_liquid;
    // 30 µm outside the outline (80 µm east of the centre): over liquid, the same verdict for
    // the mount's mineral.
    const pmsim::BeckeProbe off = pmsim::probe_becke_line(*specimen, scene, x_fraction(scene, 80.0), 0.5);
    EXPECT_FALSE(off.on_fragment);
    EXPECT_DOUBLE_EQ(off.mineral_n, 1.60);
    EXPECT_EQ(off.moves_into_mineral, expected);
  }
}

TEST(BeckeProbe, MatchWithinAThousandthIsReportedAsNoLine) {
  OneFragment f;
  f.n_liquid = 1.6005;  // |Δn| = 5e-4 < the probe's 0.001 match
  const auto specimen = make_specimen(f);
  const pmsim::BeckeProbe p = pmsim::probe_becke_line(*specimen, probe_scene(), 0.5, 0.5);
  EXPECT_EQ(p.moves_into_mineral, 0);
  EXPECT_NE(pmsim::describe_becke_line(p).find("matches"), std::string::npos);
}

TEST(BeckeProbe, CalciteIndexFollowsThePolarizerAndTheStage) {
  // Calcite with its c axis (the indicatrix's Z, ne) along lab x, in a liquid of 1.54:
  // ne = 1.486 < 1.54 < no = 1.658.
  OneFragment f;
  f.crystal = pmsim::Crystal::uniaxial_constant("calcite", 1.658, 1.486);
  f.orientation = glm::dmat3(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));
  const auto specimen = make_specimen(f);
  const glm::dvec3 n = f.crystal->principal_indices(kLambdaD);
  // Polarizer E–W (along c): n' = ne, the line moves out on focusing up.
  const pmsim::BeckeProbe ew = pmsim::probe_becke_line(*specimen, probe_scene(0.0), 0.5, 0.5);
  EXPECT_NEAR(ew.mineral_n, n.z, 1e-12);
  EXPECT_EQ(ew.moves_into_mineral, -1);
  // Polarizer N–S (⟂ c): n' = no, into the grain.
  const pmsim::BeckeProbe ns = pmsim::probe_becke_line(*specimen, probe_scene(90.0), 0.5, 0.5);
  EXPECT_NEAR(ns.mineral_n, n.x, 1e-12);
  EXPECT_EQ(ns.moves_into_mineral, 1);
  // Polarizer E–W with the stage turned 90°: c now lies N–S, the vibration meets no.
  const pmsim::BeckeProbe turned = pmsim::probe_becke_line(*specimen, probe_scene(0.0, 90.0), 0.5, 0.5);
  EXPECT_NEAR(turned.mineral_n, n.x, 1e-9);
  EXPECT_EQ(turned.moves_into_mineral, 1);
  // At 45° the indicatrix's radius: 1/n'² = ½/no² + ½/ne² (Nesse 2012 §7).
  const pmsim::BeckeProbe diag = pmsim::probe_becke_line(*specimen, probe_scene(45.0), 0.5, 0.5);
  EXPECT_NEAR(diag.mineral_n, 1.0 / std::sqrt(0.5 / (n.x * n.x) + 0.5 / (n.z * n.z)), 1e-12);
}
