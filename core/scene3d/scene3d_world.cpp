#include "core/scene3d/scene3d_world.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/input_error.h"
#include "core/lens/lens_embree.h"

namespace pmsim {
namespace {

// The single device error callback. It must not throw through Embree's C frames, so it records
// the first message and the builder checks it after committing.
void embree_error(void* user, RTCError code, const char* str) {
  auto* message = static_cast<std::string*>(user);
  if (message->empty())
    *message = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (str ? str : "");
}

glm::dvec3 rotate_xyz(const glm::dvec3& v, const glm::dvec3& deg) {
  glm::dmat4 m(1.0);
  m = glm::rotate(m, glm::radians(deg.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(deg.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(deg.x), glm::dvec3(1, 0, 0));
  return glm::dvec3(m * glm::dvec4(v, 0.0));
}

// Rectangle centred at c spanned by u (width) and v = n × u (height), wound counter-clockwise
// as seen from the side n points to.
void rectangle(const glm::dvec3& c, const glm::dvec3& n, const glm::dvec3& u, glm::dvec2 size,
               std::vector<glm::dvec3>& v, std::vector<glm::ivec3>& t) {
  const glm::dvec3 vv = glm::cross(n, u);
  const glm::dvec3 a = 0.5 * size.x * u, b = 0.5 * size.y * vv;
  v = {c - a - b, c + a - b, c + a + b, c - a + b};
  t = {{0, 1, 2}, {0, 2, 3}};
}

}  // namespace

Scene3dWorld::Scene3dWorld(const Scene3dDescription& desc) : desc_(desc) {
  // One kernel on every machine: Embree picks its widest ISA, and its AVX-512 and AVX2 kernels
  // round hit distances differently, enough to move a ray across a lens rim (the golden images of
  // tests/golden/, taken on an AVX-512 machine, differed by up to 0.03 on an AVX2-only one).
  device_ = rtcNewDevice("max_isa=avx2");
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  rtcSetDeviceErrorFunction(device_, embree_error, &embree_message_);
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  try {
    build();
  } catch (...) {
    // The destructor does not run for a constructor that throws.
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    throw;
  }
}

void Scene3dWorld::build() {
  const Scene3dDescription& desc = desc_;

  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  auto grow = [&](const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  grow(desc.camera.position);

  for (std::size_t i = 0; i < desc.objects.size(); ++i) {
    const Scene3dObject& o = desc.objects[i];
    const int oi = static_cast<int>(i);
    GeometryInfo info{Scene3dSurfaceKind::Diffuse, oi, o.material, -1, -1, {}, {}};
    if (o.type != Scene3dObject::Type::Lens &&
        desc.materials[o.material].type == Scene3dMaterial::Type::Glass)
      info.kind = Scene3dSurfaceKind::Glass;
    std::vector<glm::dvec3> v;
    std::vector<glm::ivec3> t;
    switch (o.type) {
      case Scene3dObject::Type::Plane:
        rectangle(o.center, o.normal, o.u_axis, o.size_mm, v, t);
        break;
      case Scene3dObject::Type::Box: {
        const glm::dvec3 h = 0.5 * o.box_size_mm;
        for (int k = 0; k < 8; ++k) {
          const glm::dvec3 c((k & 1) ? h.x : -h.x, (k & 2) ? h.y : -h.y, (k & 4) ? h.z : -h.z);
          v.push_back(o.center + rotate_xyz(c, o.rotation_deg));
        }
        // Faces by corner bits; winding fixed below so that normals point outward.
        const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                 {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
        for (const auto& f : faces) {
          glm::ivec3 a{f[0], f[1], f[2]}, b{f[0], f[2], f[3]};
          const glm::dvec3 n = glm::cross(v[a.y] - v[a.x], v[a.z] - v[a.x]);
          const glm::dvec3 fc = 0.25 * (v[f[0]] + v[f[1]] + v[f[2]] + v[f[3]]);
          if (glm::dot(n, fc - o.center) < 0.0) {
            std::swap(a.y, a.z);
            std::swap(b.y, b.z);
          }
          t.push_back(a);
          t.push_back(b);
        }
        break;
      }
      case Scene3dObject::Type::Mesh:
        v = o.vertices;
        t = o.triangles;
        break;
      case Scene3dObject::Type::Sphere: {
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        auto* p = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
        p[0] = static_cast<float>(o.center.x);
        p[1] = static_cast<float>(o.center.y);
        p[2] = static_cast<float>(o.center.z);
        p[3] = static_cast<float>(o.radius_mm);
        rtcCommitGeometry(g);
        const unsigned id = rtcAttachGeometry(scene_, g);
        rtcReleaseGeometry(g);
        info.sphere_center = o.center;
        if (geometry_.size() <= id) geometry_.resize(id + 1, info);
        geometry_[id] = info;
        grow(o.center - glm::dvec3(o.radius_mm));
        grow(o.center + glm::dvec3(o.radius_mm));
        continue;
      }
      case Scene3dObject::Type::Lens:
        add_lens(o, oi);
        continue;
    }
    for (const auto& p : v) grow(p);
    add_triangles(v, t, std::move(info));
  }
  for (std::size_t i = 0; i < desc.lights.size(); ++i) {
    const Scene3dLight& l = desc.lights[i];
    if (l.type == Scene3dLight::Type::Point) {
      grow(l.position);
      continue;
    }
    std::vector<glm::dvec3> v;
    std::vector<glm::ivec3> t;
    rectangle(l.center, l.normal, l.u_axis, l.size_mm, v, t);
    for (const auto& p : v) grow(p);
    if (!l.visible) continue;
    add_triangles(v, t, {Scene3dSurfaceKind::Emitter, -1, -1, -1, static_cast<int>(i), {}, {}});
  }
  scene_size_mm_ = std::max(1.0, glm::length(hi - lo));
  rtcCommitScene(scene_);
  if (!embree_message_.empty()) throw std::runtime_error(embree_message_);
}

Scene3dWorld::~Scene3dWorld() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void Scene3dWorld::add_triangles(const std::vector<glm::dvec3>& v, const std::vector<glm::ivec3>& t,
                                 GeometryInfo info) {
  RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) {
    vb[3 * i] = static_cast<float>(v[i].x);
    vb[3 * i + 1] = static_cast<float>(v[i].y);
    vb[3 * i + 2] = static_cast<float>(v[i].z);
  }
  auto* ib = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), t.size()));
  info.tri_normals.resize(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    ib[3 * i] = static_cast<unsigned>(t[i].x);
    ib[3 * i + 1] = static_cast<unsigned>(t[i].y);
    ib[3 * i + 2] = static_cast<unsigned>(t[i].z);
    // Counter-clockwise seen from outside: N = (v1 − v0) × (v2 − v0).
    const glm::dvec3 n = glm::cross(v[t[i].y] - v[t[i].x], v[t[i].z] - v[t[i].x]);
    const double len = glm::length(n);
    info.tri_normals[i] = len > 0.0 ? n / len : glm::dvec3(0, 0, 1);
  }
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene_, g);
  rtcReleaseGeometry(g);
  if (geometry_.size() <= id) geometry_.resize(id + 1, info);
  geometry_[id] = std::move(info);
}

void Scene3dWorld::add_lens(const Scene3dObject& o, int object_index) {
  LensSpec spec;
  try {
    spec = lens_spec_from_json(o.lens, desc_.file);
    lenses_.push_back(std::make_unique<Lens>(spec));
  } catch (const InputError& e) {
    throw InputError(desc_.file, o.key + (e.key.empty() ? "" : "." + e.key), e.value,
                     std::string("invalid lens: ") + e.what());
  }
  // The lens module's user geometry (double-precision LensGeometry behind Embree callbacks).
  const unsigned id = attach_lens(device_, scene_, lenses_.back()->geometry());
  GeometryInfo info{
      Scene3dSurfaceKind::Lens, object_index, -1, static_cast<int>(lenses_.size() - 1), -1, {}, {}};
  if (geometry_.size() <= id) geometry_.resize(id + 1, info);
  geometry_[id] = info;
}

bool Scene3dWorld::intersect(const glm::dvec3& origin, const glm::dvec3& dir, double t_min, double t_max,
                             Scene3dHit& hit) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(origin.x);
  rh.ray.org_y = static_cast<float>(origin.y);
  rh.ray.org_z = static_cast<float>(origin.z);
  rh.ray.dir_x = static_cast<float>(dir.x);
  rh.ray.dir_y = static_cast<float>(dir.y);
  rh.ray.dir_z = static_cast<float>(dir.z);
  rh.ray.tnear = static_cast<float>(t_min);
  rh.ray.tfar = static_cast<float>(std::min(t_max, 1e30));
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.Ng_x = rh.hit.Ng_y = rh.hit.Ng_z = 0.0f;
  rh.hit.u = rh.hit.v = 0.0f;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const GeometryInfo& g = geometry_[rh.hit.geomID];
  hit.t = rh.ray.tfar;
  hit.point = origin + hit.t * dir;
  hit.kind = g.kind;
  hit.object = g.object;
  hit.material = g.material;
  hit.lens = g.lens;
  hit.light = g.light;
  if (!g.tri_normals.empty()) {
    hit.normal = g.tri_normals[rh.hit.primID];
  } else if (g.kind == Scene3dSurfaceKind::Lens) {
    hit.normal = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  } else {
    hit.normal = glm::normalize(hit.point - g.sphere_center);
  }
  return true;
}

bool Scene3dWorld::opaque_between(const glm::dvec3& from, const glm::dvec3& to) const {
  const glm::dvec3 d = to - from;
  const double dist = glm::length(d);
  if (!(dist > 0.0)) return false;
  const glm::dvec3 dir = d / dist;
  const double eps = 1e-6 * scene_size_mm_;
  double t0 = eps;
  // Step through see-through surfaces; a closed glass body is crossed in two steps.
  for (int k = 0; k < 64; ++k) {
    Scene3dHit h;
    if (!intersect(from, dir, t0, dist - eps, h)) return false;
    if (h.kind == Scene3dSurfaceKind::Diffuse) return true;
    t0 = h.t + eps;
  }
  return true;
}

}  // namespace pmsim
