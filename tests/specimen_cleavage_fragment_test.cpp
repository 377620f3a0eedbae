// Cleavage fragments in grain mounts (issue 12: "cleavage fragments where the mineral has a good
// cleavage"): a fragment of a mineral with a perfect cleavage lies on it, so the cleavage normal
// is vertical; its outline is cut along the traces of the other cleavages (flat faces whose
// normals are those cleavages'); a mineral without cleavage keeps uniformly random orientations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "core/base/units.h"
#include "core/specimen/grain_mount.h"
#include "core/specimen/grain_mount_render.h"

namespace {

pmsim::ScatterOptions mount(const std::string& mineral) {
  pmsim::ScatterOptions o;
  o.field_width_um = o.field_height_um = 3000.0;
  o.cleavage_normals = pmsim::good_cleavage_normals(mineral);
  return o;
}

// max over k of |(R n_k)·z|: 1 when the fragment lies on one of the cleavages.
double best_vertical(const pmsim::FragmentShape& f, const std::vector<glm::dvec3>& normals) {
  double best = 0.0;
  for (const glm::dvec3& n : normals) best = std::max(best, std::abs((f.crystal_to_lab * glm::normalize(n)).z));
  return best;
}

}  // namespace

TEST(CleavageFragments, MuscoviteLiesOnItsBasalCleavage) {
  const auto o = mount("muscovite");
  ASSERT_EQ(o.cleavage_normals.size(), 1u) << "muscovite: (001) perfect, the only good cleavage";
  const auto frags = pmsim::scatter_fragments(o);
  ASSERT_GT(frags.size(), 100u);
  double worst = 1.0, c2 = 0.0, s2 = 0.0;
  for (const auto& f : frags) {
    worst = std::min(worst, best_vertical(f, o.cleavage_normals));
    // The orientation stays a rotation (det +1, orthonormal): the indicatrix is not distorted.
    EXPECT_NEAR(glm::determinant(f.crystal_to_lab), 1.0, 1e-12);
    EXPECT_TRUE(f.clip_normals.empty()) << "one cleavage: nothing to cut the outline along";
    // The crystal's X axis turned about z: its azimuth should be uniform.
    const glm::dvec3 x = f.crystal_to_lab[0];
    const double az = std::atan2(x.y, x.x);
    c2 += std::cos(2 * az), s2 += std::sin(2 * az);
  }
  // Constructed exactly: the cleavage normal is ±z to rounding (1e-12 ≈ 10⁴ ulp, angle 1.4e-6 rad).
  EXPECT_GT(worst, 1.0 - 1e-12);
  // Uniform azimuths: |mean of e^{2iφ}| ~ 1/√N; 4/√N is a 4σ bound (Rayleigh test).
  const double r = std::hypot(c2, s2) / frags.size();
  std::printf("muscovite: %zu fragments, worst |n·z| = %.15f, azimuth resultant %.3f (4/sqrt(N) = %.3f)\n",
              frags.size(), worst, r, 4.0 / std::sqrt(double(frags.size())));
  EXPECT_LT(r, 4.0 / std::sqrt(double(frags.size())));
}

TEST(CleavageFragments, CalciteLiesOnARhombohedronFaceWithTheOtherTwoAsItsEdges) {
  const auto o = mount("calcite");
  ASSERT_EQ(o.cleavage_normals.size(), 3u) << "calcite: the three {10-14} planes";
  // The data's angle between the rhombohedral cleavages: 74.9° (105.1°) — the rhombohedron's.
  const double angle = pmsim::degrees(std::acos(std::abs(glm::dot(glm::normalize(o.cleavage_normals[0]),
                                                                   glm::normalize(o.cleavage_normals[1])))));
  EXPECT_NEAR(angle, 74.9, 0.3);
  const auto frags = pmsim::scatter_fragments(o);
  ASSERT_GT(frags.size(), 100u);
  int faces[3] = {0, 0, 0};
  for (const auto& f : frags) {
    EXPECT_GT(best_vertical(f, o.cleavage_normals), 1.0 - 1e-12);
    for (int k = 0; k < 3; ++k)
      if (std::abs((f.crystal_to_lab * glm::normalize(o.cleavage_normals[k])).z) > 1.0 - 1e-12) ++faces[k];
    ASSERT_EQ(f.clip_normals.size(), 2u);
  }
  // Each of the three equivalent planes is drawn (a third each; 5σ of a binomial bound).
  const double n = frags.size(), sd = std::sqrt(n * (1.0 / 3) * (2.0 / 3));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(faces[k], n / 3, 5 * sd) << "plane " << k;

  // The outline: a fair part of the mesh's side area lies in the other two cleavage planes
  // (triangle normals within 1° of ±n), where a fragment of fracture has almost none.
  const auto plane_area_fraction = [](const pmsim::FragmentShape& f) {
    const pmsim::FragmentMesh m = pmsim::fragment_mesh(f);
    double on = 0.0, all = 0.0;
    for (const glm::uvec3& t : m.triangles) {
      const glm::dvec3 c = glm::cross(m.vertices[t.y] - m.vertices[t.x], m.vertices[t.z] - m.vertices[t.x]);
      const double a = 0.5 * glm::length(c);
      all += a;
      for (const glm::dvec3& cut : f.clip_normals)
        if (std::abs(glm::dot(glm::normalize(c), cut)) > std::cos(pmsim::radians(1.0))) {
          on += a;
          break;
        }
    }
    return on / all;
  };
  pmsim::FragmentShape cleaved = frags[0];
  pmsim::FragmentShape fractured = cleaved;
  fractured.clip_normals.clear();
  const double f_cleaved = plane_area_fraction(cleaved), f_fractured = plane_area_fraction(fractured);
  std::printf("calcite fragment 0: area on the other cleavages %.3f (without the cut %.3f)\n", f_cleaved, f_fractured);
  EXPECT_GT(f_cleaved, 0.05);
  EXPECT_LT(f_fractured, 0.01);
}

TEST(CleavageFragments, GarnetHasNoCleavageAndStaysUniformlyOriented) {
  const auto o = mount("garnet");
  EXPECT_TRUE(o.cleavage_normals.empty());
  const auto frags = pmsim::scatter_fragments(o);
  ASSERT_GT(frags.size(), 100u);
  // For uniformly random rotations the image of a fixed axis is uniform on the sphere, so its z
  // component is uniform on [−1, 1]: mean 0 (σ = 1/√(3N)), mean of z² 1/3 (σ = √(4/45/N)).
  for (int axis = 0; axis < 3; ++axis) {
    double m1 = 0.0, m2 = 0.0;
    for (const auto& f : frags) {
      const double z = f.crystal_to_lab[axis].z;
      m1 += z, m2 += z * z;
    }
    const double n = frags.size();
    m1 /= n, m2 /= n;
    std::printf("garnet axis %d: mean z %.4f, mean z^2 %.4f (N = %zu)\n", axis, m1, m2, frags.size());
    EXPECT_NEAR(m1, 0.0, 4.0 / std::sqrt(3.0 * n));
    EXPECT_NEAR(m2, 1.0 / 3.0, 4.0 * std::sqrt(4.0 / 45.0 / n));
  }
  // And the mount is the one drawn before cleavage fragments existed (same draws): no clip.
  for (const auto& f : frags) EXPECT_TRUE(f.clip_normals.empty());
}
