// Bunge Euler angles against rotations whose axes can be written down by hand.
#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/base/units.h"
#include "core/crystal/euler_angles.h"

namespace pmsim {
namespace {

void expect_vec(const glm::dvec3& got, const glm::dvec3& want) {
  // 1e-12: a handful of products of sines and cosines of exact angles, rounding only.
  EXPECT_NEAR(got.x, want.x, 1e-12);
  EXPECT_NEAR(got.y, want.y, 1e-12);
  EXPECT_NEAR(got.z, want.z, 1e-12);
}

TEST(EulerBunge, ZeroIsIdentity) {
  const glm::dmat3 m = crystal_to_sample_from_bunge({0, 0, 0});
  expect_vec(m[0], {1, 0, 0});
  expect_vec(m[1], {0, 1, 0});
  expect_vec(m[2], {0, 0, 1});
}

TEST(EulerBunge, Phi1TurnsTheCrystalAboutSpecimenZ) {
  // φ1 = 90°: the specimen frame is rotated by +90° onto the crystal frame, so the crystal's a
  // (e1) lies along specimen +y, and e2 along −x (Bunge 1982 §2.2, a passive rotation g).
  const glm::dmat3 m = crystal_to_sample_from_bunge({radians(90.0), 0, 0});
  expect_vec(m[0], {0, 1, 0});
  expect_vec(m[1], {-1, 0, 0});
  expect_vec(m[2], {0, 0, 1});
}

TEST(EulerBunge, PhiTiltsCAboutA) {
  // Φ = 90° alone: rotation about x; c* (e3) goes from +z to −y, e2 from +y to +z.
  const glm::dmat3 m = crystal_to_sample_from_bunge({0, radians(90.0), 0});
  expect_vec(m[0], {1, 0, 0});
  expect_vec(m[1], {0, 0, 1});
  expect_vec(m[2], {0, -1, 0});
}

TEST(EulerBunge, RoundTripOverRandomOrientations) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const EulerBunge e{2 * kPi * u(rng), std::acos(1 - 2 * u(rng)), 2 * kPi * u(rng)};
    const glm::dmat3 m = crystal_to_sample_from_bunge(e);
    const glm::dmat3 back = crystal_to_sample_from_bunge(bunge_from_crystal_to_sample(m));
    // 1e-9: atan2 of entries with |sin Φ| ≥ ~1e-3 loses at most ~1e-13/1e-3 in angle.
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) ASSERT_NEAR(back[c][r], m[c][r], 1e-9) << i;
    EXPECT_NEAR(glm::determinant(m), 1.0, 1e-12);
  }
}

TEST(EulerBunge, GimbalLockKeepsTheRotation) {
  for (double Phi : {0.0, kPi}) {
    const glm::dmat3 m = crystal_to_sample_from_bunge({radians(30.0), Phi, radians(50.0)});
    const EulerBunge e = bunge_from_crystal_to_sample(m);
    EXPECT_EQ(e.phi2_rad, 0.0);
    const glm::dmat3 back = crystal_to_sample_from_bunge(e);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(back[c][r], m[c][r], 1e-12);
  }
}

TEST(EulerBunge, RejectsReflectionsAndNonOrthonormal) {
  glm::dmat3 mirror(1.0);
  mirror[2][2] = -1.0;
  EXPECT_THROW(bunge_from_crystal_to_sample(mirror), std::invalid_argument);
  glm::dmat3 scaled(1.0);
  scaled[0][0] = 1.1;
  EXPECT_THROW(bunge_from_crystal_to_sample(scaled), std::invalid_argument);
}

}  // namespace
}  // namespace pmsim
