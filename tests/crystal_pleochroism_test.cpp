// Pleochroism: the colour of an absorbing crystal in plane-polarized light changes as the stage
// turns because absorption depends on the vibration direction.
#include <cmath>

#include <gtest/gtest.h>

#include "core/base/units.h"
#include "core/crystal/plate.h"

using namespace pmsim;

namespace {

// Plane-polarized light (polarizer E–W, analyzer out): transmitted intensity at normal incidence.
double ppl_intensity(const Crystal& c, const glm::dmat3& orient, double stage_rad, double wl,
                     double d = 30.0) {
  PlateSpec p;
  p.crystal = &c;
  p.crystal_to_lab = rotate_stage(orient, stage_rad);
  p.thickness_um = d;
  p.fresnel = false;
  return (plate_jones(p, {0, 0, 1}, wl) * JonesVector{1.0, 0.0}).intensity();
}
}  // namespace

TEST(Pleochroism, BiotiteIsPaleAcrossAndDarkAlongTheCleavage) {
  const Crystal& b = find_mineral("biotite");
  ASSERT_TRUE(b.absorbing());
  // Section ⟂ cleavage: X (⟂ (001)) along lab x, Z along lab y, Y along the microscope axis.
  const glm::dmat3 R = biaxial_orientation({1, 0, 0}, {0, 1, 0});
  // Beer–Lambert with the 30 µm transmittances of biotite.json (X: 0.85, Z: 0.08 at 550 nm);
  // normal incidence, no Fresnel: exact up to rounding (1e-12).
  EXPECT_NEAR(ppl_intensity(b, R, 0.0, 550.0), 0.85, 1e-12);
  EXPECT_NEAR(ppl_intensity(b, R, kPi / 2, 550.0), 0.08, 1e-12);
  // In between the modes are linear and share the light as cos², sin² (no analyzer, so the
  // retardation does not enter): I(φ) = cos²φ·T_X + sin²φ·T_Z.
  const double phi = 0.5;
  EXPECT_NEAR(ppl_intensity(b, R, phi, 550.0),
              std::pow(std::cos(phi), 2) * 0.85 + std::pow(std::sin(phi), 2) * 0.08, 1e-12);
}

TEST(Pleochroism, TransmittedSpectrumChangesWithStageRotation) {
  for (const char* name : {"biotite", "hornblende", "tourmaline"}) {
    const Crystal& c = find_mineral(name);
    const glm::dmat3 R = c.symmetry() == CrystalSymmetry::Uniaxial
                             ? uniaxial_orientation({1, 0, 0})
                             : biaxial_orientation({1, 0, 0}, {0, 1, 0});
    // Blue/red ratio of the transmitted light at stage 0° and 90°: a colour change shows as a
    // change of spectral shape, not only of brightness. The tables differ by > 10 % in shape.
    const double r0 = ppl_intensity(c, R, 0.0, 450.0) / ppl_intensity(c, R, 0.0, 650.0);
    const double r90 = ppl_intensity(c, R, kPi / 2, 450.0) / ppl_intensity(c, R, kPi / 2, 650.0);
    EXPECT_GT(std::abs(r0 / r90 - 1.0), 0.1) << name;
    // And a 180° turn restores it (absorption depends on the vibration axis, not its sense).
    EXPECT_NEAR(ppl_intensity(c, R, kPi, 450.0), ppl_intensity(c, R, 0.0, 450.0), 1e-12) << name;
  }
}

TEST(Pleochroism, TourmalineIsDarkestWithItsAxisAcrossThePolarizer) {
  const Crystal& t = find_mineral("tourmaline");
  const glm::dmat3 R = uniaxial_orientation({1, 0, 0});  // c along the polarizer
  // The ordinary ray (vibrating ⟂ c) is absorbed much more strongly (Nesse 2012): E 0.78 vs O 0.04.
  EXPECT_GT(ppl_intensity(t, R, 0.0, 550.0), 10 * ppl_intensity(t, R, kPi / 2, 550.0));
}

TEST(Pleochroism, NonAbsorbingCrystalsAreUnchangedAndOpaqueOnesStayFinite) {
  const Crystal& q = find_mineral("calcite");
  EXPECT_FALSE(q.absorbing());
  EXPECT_NEAR(ppl_intensity(q, uniaxial_orientation({1, 1, 0}), 0.3, 550.0), 1.0, 1e-12);  // lossless
  // 10 mm of biotite: e^(−μd) underflows far below any display level; must stay finite, ≥ 0.
  const Crystal& b = find_mineral("biotite");
  const double I = ppl_intensity(b, biaxial_orientation({1, 0, 0}, {0, 1, 0}), kPi / 2, 400.0, 1e4);
  EXPECT_TRUE(std::isfinite(I));
  EXPECT_LT(I, 1e-100);
}
