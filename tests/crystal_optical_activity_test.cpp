// Optical activity of quartz: rotation of the plane of polarization along the optic axis.
#include <cmath>

#include <gtest/gtest.h>

#include "core/base/units.h"
#include "core/crystal/plate.h"

using namespace pmsim;

namespace {

PlateSpec quartz_perp_c(double d_um) {
  PlateSpec p;
  p.crystal = &find_mineral("quartz");
  p.crystal_to_lab = uniaxial_orientation({0, 0, 1});
  p.thickness_um = d_um;
  p.fresnel = false;
  return p;
}
}  // namespace

TEST(OpticalActivity, QuartzPerpendicularToCRotatesBy21point7DegreesPerMillimetre) {
  const JonesVector out = plate_jones(quartz_perp_c(1000.0), {0, 0, 1}, 589.3) * JonesVector{1.0, 0.0};
  // The output stays linear: the two components are in phase (ratio real to 1e-12).
  const complexd ratio = out.y / out.x;
  EXPECT_NEAR(ratio.imag(), 0.0, 1e-12);
  const double angle_deg = degrees(std::atan(ratio.real()));
  // Right-handed quartz is dextrorotatory: clockwise for the observer, i.e. a negative angle in
  // the lab convention. 21.72°/mm (CRC Handbook) within 0.1° (fit residual of ρ(λ)).
  EXPECT_NEAR(angle_deg, -21.72, 0.1);
  EXPECT_NEAR(out.intensity(), 1.0, 1e-12);  // lossless without Fresnel
}

TEST(OpticalActivity, RotationIsDispersiveAndProportionalToThickness) {
  auto rot = [](double d, double wl) {
    const JonesVector o = plate_jones(quartz_perp_c(d), {0, 0, 1}, wl) * JonesVector{1.0, 0.0};
    return std::atan2(o.y.real(), o.x.real());
  };
  const double rho = find_mineral("quartz").rotatory_power_rad_per_um(546.1);
  // Pure rotation along the axis: angle = −ρ·d exactly within the model (1e-12 rad).
  EXPECT_NEAR(rot(500.0, 546.1), -rho * 500.0, 1e-12);
  EXPECT_NEAR(rot(250.0, 546.1), 0.5 * rot(500.0, 546.1), 1e-12);
  // Shorter wavelengths turn more (rotatory dispersion): 405 nm turns about twice as much as 589 nm.
  EXPECT_GT(std::abs(rot(1000.0, 404.7)), 2.0 * std::abs(rot(1000.0, 589.3)));
}

TEST(OpticalActivity, CentreOfAThinSectionFigureIsNotBlack) {
  // 30 µm quartz ⟂ c between crossed polars at normal incidence: I = sin²(ρd) (not 0 as for an
  // inactive crystal); ρd ≈ 0.65° at 589 nm.
  const double rho = find_mineral("quartz").rotatory_power_rad_per_um(589.3);
  const JonesMatrix J = plate_jones(quartz_perp_c(30.0), {0, 0, 1}, 589.3);
  const double I = (linear_polarizer(kPi / 2) * (J * JonesVector{1.0, 0.0})).intensity();
  EXPECT_NEAR(I, std::pow(std::sin(rho * 30.0), 2), 1e-15);
  EXPECT_GT(I, 1e-4);
  // A 3 mm plate shows a coloured centre: sin²(ρ(λ)·d) differs by colour (0.81 at 450 nm, 0.64 at
  // 650 nm), each exact within the model to rounding.
  const Crystal& q = find_mineral("quartz");
  for (double wl : {450.0, 650.0}) {
    const JonesMatrix Jw = plate_jones(quartz_perp_c(3000.0), {0, 0, 1}, wl);
    const double Iw = (linear_polarizer(kPi / 2) * (Jw * JonesVector{1.0, 0.0})).intensity();
    EXPECT_NEAR(Iw, std::pow(std::sin(q.rotatory_power_rad_per_um(wl) * 3000.0), 2), 1e-12) << wl;
  }
  EXPECT_GT(std::pow(std::sin(q.rotatory_power_rad_per_um(450.0) * 3000.0), 2) -
                std::pow(std::sin(q.rotatory_power_rad_per_um(650.0) * 3000.0), 2),
            0.1);
}

TEST(OpticalActivity, AwayFromTheAxisLinearBirefringenceDominates) {
  const PlateSpec p = quartz_perp_c(1000.0);
  // Ray in the xz plane at sin θ_air = 0.5: the o and e modes are TE and TM. Polarizer along p
  // (basis a = x here), crossed analyzer. With activity the eigenmodes are elliptical with axis
  // ratio ~ α/(δ/2); the light leaking into the crossed analyzer is at most (2α/Δ)² where
  // Δ = √(δ² + 4α²) (Jones' N-matrix), which is ≈ 4e-3 here against sin²(ρd) = 0.14 on the axis.
  const double s = 0.5;
  const glm::dvec3 k(s, 0, std::sqrt(1 - s * s));
  const JonesMatrix J = plate_jones(p, k, 589.3);
  const double I = (linear_polarizer(kPi / 2) * (J * JonesVector{1.0, 0.0})).intensity();
  const PlateModes m = plate_modes(p, k, 589.3);
  const double delta = 2 * kPi * m.retardation_nm / 589.3;
  const double ct = (0.5 * (m.s1 + m.s2)).z / glm::length(0.5 * (m.s1 + m.s2));
  const double alpha = find_mineral("quartz").rotatory_power_rad_per_um(589.3) * ct * ct * 1000.0 / ct;
  const double bound = 4 * alpha * alpha / (delta * delta + 4 * alpha * alpha);
  EXPECT_LE(I, bound * (1 + 1e-9));
  EXPECT_LT(I, 0.01);
  EXPECT_GT(delta, 5.0);  // many radians of linear retardance
}
