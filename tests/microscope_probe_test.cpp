// The teaching-panel probes: spectrum, retardation and order at the cursor, and the figure's
// description (sign, 2V, compensator rule).
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/base/input_error.h"
#include "core/microscope/figure_info.h"
#include "core/microscope/pixel_probe.h"
#include "core/microscope/section_map.h"

using namespace pmsim;

TEST(PixelProbe, PlateAt45ShowsItsRetardationAndSinSquaredSpectrum) {
  Scene s;
  s.sample.crystal = CrystalIndices{true, 1.540, 1.550};  // Δn = 0.010, non-dispersive
  s.sample.optic_axis = {std::sqrt(0.5), std::sqrt(0.5), 0.0};
  s.sample.thickness_um = 55.0;  // Γ = 550 nm
  const PixelProbe p = probe_pixel(s, 0.3, 0.7);
  ASSERT_TRUE(p.lit);
  ASSERT_EQ(p.wavelength_nm.size(), 81u);
  EXPECT_DOUBLE_EQ(p.wavelength_nm.front(), 380.0);
  EXPECT_DOUBLE_EQ(p.wavelength_nm.back(), 780.0);
  // Γ = d·Δn at normal incidence (exact for the plate model).
  EXPECT_NEAR(p.retardation_nm, 550.0, 1e-6);
  EXPECT_NEAR(p.order, 1.0, 1e-8);
  for (std::size_t i = 0; i < p.wavelength_nm.size(); ++i) {
    const double want = std::pow(std::sin(kPi * 550.0 / p.wavelength_nm[i]), 2);
    // Fresnel loss at the faces (n 1.54–1.55 against the mounting medium) < 1e-4.
    EXPECT_NEAR(p.transmission[i], want, 1e-3) << p.wavelength_nm[i];
  }
}

// An opaque plate (ilmenite, k = 0.1: 30 µm passes nothing, crystal_opaque_test) has no
// interference colour to read: the probe says opaque, gives no retardation, and the transmitted
// spectrum is 0 at every wavelength; the figure description says opaque; a quartz plate of the
// same cut is not opaque.
TEST(PixelProbe, OpaquePlateShowsNoLightAndNoRetardation) {
  Scene s;
  s.sample.mineral = "ilmenite";
  s.sample.optic_axis = {std::sqrt(0.5), std::sqrt(0.5), 0.0};
  s.sample.thickness_um = 30.0;
  const PixelProbe p = probe_pixel(s, 0.5, 0.5);
  ASSERT_TRUE(p.lit);
  EXPECT_TRUE(p.opaque);
  EXPECT_EQ(p.retardation_nm, 0.0);
  EXPECT_EQ(p.order, 0.0);
  for (double t : p.transmission) EXPECT_EQ(t, 0.0);
  // Nor a figure: the conoscope shows black, not ilmenite's uniaxial negative cross.
  Scene cono = s;
  cono.mode = ViewMode::Cono;
  cono.bertrand_in = true;
  const FigureInfo f = describe_figure(cono);
  EXPECT_EQ(f.kind, "opaque");
  EXPECT_TRUE(f.optic_sign.empty());
  EXPECT_NE(f.summary.find("no interference figure"), std::string::npos) << f.summary;
  s.sample.mineral = "quartz";
  const PixelProbe q = probe_pixel(s, 0.5, 0.5);
  EXPECT_FALSE(q.opaque);
  EXPECT_NEAR(q.retardation_nm, 30.0 * 1000.0 * 0.0091, 10.0);  // δ ≈ 0.009 at 550 nm
}

TEST(PixelProbe, WedgeRetardationGrowsLeftToRightAndSectionsNameTheirMinerals) {
  Scene w;
  w.sample.type = SampleType::Wedge;
  w.sample.crystal = CrystalIndices{true, 1.540, 1.550};
  w.sample.thickness_um = 200.0;
  // Thickness 0 at the left edge, 200 µm at the right: at x = 1/4 the plate is 50 µm, Γ = 500 nm.
  EXPECT_NEAR(probe_pixel(w, 0.25, 0.5).retardation_nm, 500.0, 1e-6);
  EXPECT_NEAR(probe_pixel(w, 0.0, 0.5).retardation_nm, 0.0, 1e-9);
  Scene g;
  g.sample.type = SampleType::Section;
  g.sample.section = "granite_hand_placed";
  const PixelProbe p = probe_pixel(g, 0.5, 0.5);
  // The centre pixel names the mineral of the domain under it: the section's own.
  const auto granite = load_section("granite_hand_placed");
  const glm::dvec2 centre{0.0, 0.0};
  EXPECT_EQ(p.mineral, granite->mineral_of_domain(granite->domain_at(centre)));
}

TEST(PixelProbe, OutsideTheConoscopicDiskIsUnlit) {
  Scene s;
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  EXPECT_FALSE(probe_pixel(s, 0.01, 0.01).lit);
  EXPECT_TRUE(probe_pixel(s, 0.5, 0.5).lit);
}

TEST(FigureInfo, UniaxialSignsAndTheGypsumRule) {
  Scene s;
  s.mode = ViewMode::Cono;
  s.sample.optic_axis = {0, 0, 1};
  s.sample.mineral = "calcite";
  FigureInfo f = describe_figure(s);
  EXPECT_EQ(f.kind, "uniaxial");
  EXPECT_EQ(f.optic_sign, "negative");  // calcite: ne < no
  EXPECT_EQ(f.orientation, "centred optic-axis figure");
  s.sample.mineral = "quartz";
  s.compensator = Compensator::Gypsum;
  f = describe_figure(s);
  EXPECT_EQ(f.optic_sign, "positive");
  EXPECT_EQ(f.compensator.rfind("addition", 0), 0u) << f.compensator;  // addition in NE–SW first
}

TEST(FigureInfo, BiaxialTwoVFromTheIndices) {
  Scene s;
  s.sample.crystal = CrystalIndices{false, 1.5, 1.5, 1.5};
  s.sample.crystal->nalpha = 1.60;
  s.sample.crystal->nbeta = 1.61;
  s.sample.crystal->ngamma = 1.64;
  s.sample.x_axis = {1, 0, 0};
  s.sample.z_axis = {0, 0, 1};
  const FigureInfo f = describe_figure(s);
  EXPECT_EQ(f.kind, "biaxial");
  EXPECT_EQ(f.optic_sign, "positive");  // nγ − nβ > nβ − nα: Z is the acute bisectrix
  // cos²Vz = nα²(nγ² − nβ²)/(nβ²(nγ² − nα²)) → 2Vz ≈ 61.0°
  const double c2 = 1.60 * 1.60 * (1.64 * 1.64 - 1.61 * 1.61) / (1.61 * 1.61 * (1.64 * 1.64 - 1.60 * 1.60));
  EXPECT_NEAR(f.two_v_deg, 2.0 * std::acos(std::sqrt(c2)) * 180.0 / kPi, 1e-6);
  EXPECT_EQ(f.orientation, "acute bisectrix figure");
}

TEST(FigureInfo, InvalidSceneIsAnInputError) {
  Scene s;
  s.sample.thickness_um = -3;
  EXPECT_THROW(describe_figure(s), InputError);
  EXPECT_THROW(probe_pixel(s, 0.5, 0.5), InputError);
}
