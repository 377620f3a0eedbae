// Lenses as Embree user geometry: one RTCScene with two lenses and a triangle plane.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "core/lens/lens_embree.h"

using namespace pmsim;

namespace {
LensSpec lens_at(glm::dvec3 c, double R) {
  LensSpec s;
  s.center = c;
  s.radius_mm = 4.25;
  s.front_radius_mm = R;
  s.back_radius_mm = -R;
  s.ledge_mm = 0.3;
  return s;
}

struct Scene {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  LensGeometry a{lens_at({-10, 0, 0}, 8.0)}, b{lens_at({10, 0, 0}, 4.3)};
  unsigned id_a, id_b, id_plane;
  Scene() {
    id_a = attach_lens(device, scene, a);
    id_b = attach_lens(device, scene, b);
    // Plane z = 20 spanning |x|,|y| ≤ 50: two triangles.
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float* v = (float*)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                               3 * sizeof(float), 4);
    const float verts[12] = {-50, -50, 20, 50, -50, 20, 50, 50, 20, -50, 50, 20};
    std::copy(verts, verts + 12, v);
    unsigned* idx = (unsigned*)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                       3 * sizeof(unsigned), 2);
    const unsigned tris[6] = {0, 1, 2, 0, 2, 3};
    std::copy(tris, tris + 6, idx);
    rtcCommitGeometry(g);
    id_plane = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
  }
  ~Scene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  RTCRayHit shoot(glm::dvec3 o, glm::dvec3 d, float tnear = 0.0f) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = float(o.x), rh.ray.org_y = float(o.y), rh.ray.org_z = float(o.z);
    rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
    rh.ray.tnear = tnear;
    rh.ray.tfar = INFINITY;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    return rh;
  }
};
}  // namespace

TEST(LensEmbreeScene, RaysFindTheRightLensOrThePlaneWithDoubleGeometryToFloatPrecision) {
  Scene s;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  int n_a = 0, n_b = 0, n_plane = 0;
  for (int k = 0; k < 3000; ++k) {
    // Rays from z = −10 toward the plane, scanning x ∈ [−20, 20]; direction slightly scaled (non-unit).
    const glm::dvec3 o{20 * u(rng), 6 * u(rng), -10};
    const glm::dvec3 d = 2.0 * glm::normalize(glm::dvec3(0.05 * u(rng), 0.05 * u(rng), 1));
    const RTCRayHit rh = s.shoot(o, d);
    ASSERT_NE(rh.hit.geomID, RTC_INVALID_GEOMETRY_ID);
    const glm::dvec3 of{rh.ray.org_x, rh.ray.org_y, rh.ray.org_z};
    const glm::dvec3 df{rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z};
    const LensGeometry* lens = rh.hit.geomID == s.id_a ? &s.a : rh.hit.geomID == s.id_b ? &s.b : nullptr;
    LensHit h;
    bool hits_a = s.a.intersect(of, glm::normalize(df), 1e30, LensSurface::None, h);
    bool hits_b = s.b.intersect(of, glm::normalize(df), 1e30, LensSurface::None, h);
    if (!lens) {
      ++n_plane;
      EXPECT_EQ(rh.hit.geomID, s.id_plane);
      EXPECT_FALSE(hits_a || hits_b);  // the plane is hit only where no lens is in the way
      EXPECT_NEAR(of.z + rh.ray.tfar * df.z, 20.0, 1e-4);  // float ray arithmetic
      continue;
    }
    (lens == &s.a ? n_a : n_b)++;
    ASSERT_TRUE(lens->intersect(of, glm::normalize(df), 1e30, LensSurface::None, h));
    // Same hit as the double-precision geometry on the same (float) ray: t in units of dir.
    EXPECT_NEAR(rh.ray.tfar, h.t / glm::length(df), 1e-6 * h.t);
    const glm::dvec3 Ng{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
    EXPECT_NEAR(glm::length(Ng - h.normal), 0.0, 1e-6);  // normal rounded to float
    EXPECT_LT(glm::dot(Ng, df), 0.0);                    // outward: faces the incoming ray
    EXPECT_EQ(lens_surface_from_hit_u(rh.hit.u), h.surface);
  }
  EXPECT_GT(n_a, 100);
  EXPECT_GT(n_b, 100);
  EXPECT_GT(n_plane, 100);
}

TEST(LensEmbreeScene, OcclusionAndTnearAreHonoured) {
  Scene s;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r{};
  r.org_x = -10, r.org_y = 0, r.org_z = -10;
  r.dir_x = 0, r.dir_y = 0, r.dir_z = 1;
  r.tnear = 0, r.tfar = 5;  // stops before lens a (its front vertex is at z ≈ −1.4)
  r.mask = ~0u;
  rtcOccluded1(s.scene, &ctx, &r);
  EXPECT_EQ(r.tfar, 5.0f);  // not occluded
  r.tfar = 100;
  rtcOccluded1(s.scene, &ctx, &r);
  EXPECT_EQ(r.tfar, -INFINITY);  // occluded by lens a
  // From inside lens a (tnear past its front cap) the next hit is its back cap.
  const RTCRayHit rh = s.shoot({-10, 0, -10}, {0, 0, 1}, 10.0f);
  EXPECT_EQ(rh.hit.geomID, s.id_a);
  EXPECT_NEAR(-10 + rh.ray.tfar, s.a.thickness_mm() / 2, 1e-5);
  EXPECT_EQ(lens_surface_from_hit_u(rh.hit.u), LensSurface::Back);
}
