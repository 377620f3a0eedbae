// Bunge Euler angles against rotations whose axes can be written down by hand.
#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/base/units.h"
#include "core/crystal/axis_rotation.h"
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

// Rodrigues against the closed forms: a quarter turn about z takes x to y; the smallest rotation
// taking a to b takes a to b, keeps a × b fixed, is proper orthonormal, and turns by the angle
// between them (trace = 1 + 2 cos θ). Tolerance 1e-12: a few roundings of order-1 terms.
TEST(AxisRotation, RodriguesAndTheSmallestRotationBetweenTwoDirections) {
  const glm::dvec3 y = axis_rotation({0, 0, 1}, radians(90.0)) * glm::dvec3(1, 0, 0);
  EXPECT_NEAR(y.x, 0.0, 1e-12);
  EXPECT_NEAR(y.y, 1.0, 1e-12);
  EXPECT_NEAR(y.z, 0.0, 1e-12);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n;
  for (int k = 0; k < 200; ++k) {
    const glm::dvec3 a = glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
    const glm::dvec3 b = glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
    const glm::dmat3 Q = rotation_taking(a, b);
    const glm::dvec3 qa = Q * a, axis = glm::cross(a, b), qaxis = Q * axis;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(qa[i], b[i], 1e-12);
      EXPECT_NEAR(qaxis[i], axis[i], 1e-12);
    }
    EXPECT_NEAR(glm::determinant(Q), 1.0, 1e-12);
    const glm::dmat3 QtQ = glm::transpose(Q) * Q;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(QtQ[c][r], c == r ? 1.0 : 0.0, 1e-12);
    EXPECT_NEAR(Q[0][0] + Q[1][1] + Q[2][2], 1.0 + 2.0 * glm::dot(a, b), 1e-12);
  }
  const glm::dmat3 same = rotation_taking({0, 1, 0}, {0, 1, 0});  // parallel: the identity
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_EQ(same[c][r], c == r ? 1.0 : 0.0);
}

}  // namespace
}  // namespace pmsim
