#include "core/lens/lens_embree.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace pmsim {

namespace {

void lens_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* lens = static_cast<const LensGeometry*>(args->geometryUserPtr);
  glm::dvec3 lo, hi;
  lens->bounds(lo, hi);
  // Round outward to float so the box still encloses the double-precision surface.
  const double pad = 1e-6 * lens->size_mm();
  RTCBounds* b = args->bounds_o;
  b->lower_x = std::nextafter(float(lo.x - pad), -INFINITY);
  b->lower_y = std::nextafter(float(lo.y - pad), -INFINITY);
  b->lower_z = std::nextafter(float(lo.z - pad), -INFINITY);
  b->upper_x = std::nextafter(float(hi.x + pad), INFINITY);
  b->upper_y = std::nextafter(float(hi.y + pad), INFINITY);
  b->upper_z = std::nextafter(float(hi.z + pad), INFINITY);
}

// Nearest lens hit in (tnear, tfar) of an Embree ray, t in units of the ray's dir.
bool hit_lens(const LensGeometry& lens, RTCRayN* ray, unsigned N, unsigned i, LensHit& h, double& t) {
  const glm::dvec3 o{RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i)};
  const glm::dvec3 d{RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)};
  const double len = glm::length(d);
  if (!(len > 0.0)) return false;
  const double tnear = std::max(0.0f, RTCRayN_tnear(ray, N, i));
  const double tfar = RTCRayN_tfar(ray, N, i);
  if (!(tfar > tnear)) return false;
  const glm::dvec3 dn = d / len;
  if (!lens.intersect(o + (tnear * len) * dn, dn, (tfar - tnear) * len, LensSurface::None, h)) return false;
  t = tnear + h.t / len;
  return t < tfar;
}

void lens_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto* lens = static_cast<const LensGeometry*>(args->geometryUserPtr);
  const unsigned N = args->N;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, N);
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] != -1) continue;
    LensHit h;
    double t;
    if (!hit_lens(*lens, ray, N, i, h, t)) continue;
    RTCRayN_tfar(ray, N, i) = float(t);
    RTCHitN_Ng_x(hit, N, i) = float(h.normal.x);
    RTCHitN_Ng_y(hit, N, i) = float(h.normal.y);
    RTCHitN_Ng_z(hit, N, i) = float(h.normal.z);
    RTCHitN_u(hit, N, i) = float(static_cast<int>(h.surface));
    RTCHitN_v(hit, N, i) = 0.0f;
    RTCHitN_primID(hit, N, i) = args->primID;
    RTCHitN_geomID(hit, N, i) = args->geomID;
    for (unsigned l = 0; l < RTC_MAX_INSTANCE_LEVEL_COUNT; ++l)
      RTCHitN_instID(hit, N, i, l) = args->context->instID[l];
  }
}

void lens_occluded(const RTCOccludedFunctionNArguments* args) {
  const auto* lens = static_cast<const LensGeometry*>(args->geometryUserPtr);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] != -1) continue;
    LensHit h;
    double t;
    if (hit_lens(*lens, args->ray, N, i, h, t)) RTCRayN_tfar(args->ray, N, i) = -INFINITY;
  }
}

}  // namespace

unsigned attach_lens(RTCDevice device, RTCScene scene, const LensGeometry& lens) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, 1);
  rtcSetGeometryUserData(g, const_cast<LensGeometry*>(&lens));
  rtcSetGeometryBoundsFunction(g, lens_bounds, nullptr);
  rtcSetGeometryIntersectFunction(g, lens_intersect);
  rtcSetGeometryOccludedFunction(g, lens_occluded);
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  return id;
}

}  // namespace pmsim
