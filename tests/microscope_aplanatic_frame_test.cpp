// The ideal objective/condenser maps polarization like an aplanatic lens (Richards & Wolf 1959):
// checked against their closed-form focal field for x-polarized input, and for the properties the
// conoscopic figure relies on.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/base/units.h"
#include "core/crystal/plate.h"
#include "core/microscope/lens_polarization.h"

using namespace pmsim;

namespace {
glm::dvec3 direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}
glm::dvec3 image_in_3d(const glm::dmat2& F, const glm::dvec3& k, int column) {
  glm::dvec3 a, b;
  transverse_basis(k, a, b);
  return F[column][0] * a + F[column][1] * b;
}
}  // namespace

TEST(AplanaticFrame, XPolarizedPupilFieldMatchesRichardsWolf) {
  // Richards & Wolf (1959) eq. (2.18) without the apodisation factor: x-polarized light at pupil
  // azimuth φ leaves along θ with field ∝ (cosθ cos²φ + sin²φ, (cosθ − 1) cosφ sinφ, −sinθ cosφ),
  // a unit vector. Tolerance 1e-12: both sides are a few products of sines and cosines.
  for (double theta : {0.1, 0.6, 1.0, 1.4})
    for (double phi : {0.0, 0.3, kPi / 4, 2.0, 4.0}) {
      const glm::dvec3 k = direction(theta, phi);
      const glm::dvec3 got = image_in_3d(aplanatic_frame(k), k, 0);
      const double c = std::cos(phi), s = std::sin(phi), ct = std::cos(theta);
      const glm::dvec3 want{ct * c * c + s * s, (ct - 1.0) * c * s, -std::sin(theta) * c};
      EXPECT_NEAR(glm::length(got - want), 0.0, 1e-12) << "θ " << theta << " φ " << phi;
    }
}

TEST(AplanaticFrame, IsARotationThatIsIdentityOnTheAxisAndOnThePolarPlanes) {
  // A non-polarizing lens neither attenuates nor mirrors the field: det = +1, FᵀF = I (1e-12).
  for (double theta : {0.0, 0.5, 1.2})
    for (double phi : {0.0, 0.7, 2.5}) {
      const glm::dmat2 F = aplanatic_frame(direction(theta, phi));
      const glm::dmat2 P = glm::transpose(F) * F;
      EXPECT_NEAR(P[0][0], 1.0, 1e-12);
      EXPECT_NEAR(P[1][1], 1.0, 1e-12);
      EXPECT_NEAR(P[0][1], 0.0, 1e-12);
      EXPECT_NEAR(F[0][0] * F[1][1] - F[1][0] * F[0][1], 1.0, 1e-12);
    }
  // In the planes of the polarizer and analyzer (φ = 0°, 90°) the radial and azimuthal directions
  // are x and y themselves, so the isogyres stay on the cross hairs: F = I there (1e-12).
  for (double phi : {0.0, kPi / 2, kPi})
    for (double theta : {0.0, 0.8}) {
      const glm::dmat2 F = aplanatic_frame(direction(theta, phi));
      EXPECT_NEAR(std::fabs(F[0][0]), 1.0, 1e-12) << phi;
      EXPECT_NEAR(F[0][1], 0.0, 1e-12) << phi;
    }
}

TEST(AplanaticFrame, DiffersFromProjectingTheLabAxisAtHighAperture) {
  // The projection of x̂ onto the plane ⟂ k turns the field about twice as far as the lens does
  // (second order in θ: −θ²·cs versus −θ²/2·cs); at NA 0.85 on the diagonal the two differ by
  // several degrees, which is what made the conoscopic figure 4.6 CIEDE2000 off. Require > 3°.
  const glm::dvec3 k = direction(std::asin(0.85), kPi / 4);
  glm::dvec3 a, b;
  transverse_basis(k, a, b);  // a is the projected x̂
  const glm::dvec3 lens_x = image_in_3d(aplanatic_frame(k), k, 0);
  const double angle_deg = degrees(std::acos(std::min(1.0, glm::dot(lens_x, a))));
  EXPECT_GT(angle_deg, 3.0);
}
