#include "core/bench/lens_throughput.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <random>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include "core/base/units.h"
#include "core/lens/lens.h"
#include "core/lens/lens_embree.h"
#include "core/lens/lens_tracer.h"
#include "core/microscope/sample_source.h"

namespace pmsim {

namespace {

// CPU time of the calling thread: every measurement here runs on one thread (Embree device
// "threads=1"), and on a shared machine wall time counts the other processes' turns as well (under
// load average 5 on 2 cores the wall-clock rates of one run spread 0.17–0.42 M/s for the same
// work, the CPU-time rates 1.5–1.6 M/s), so rays per CPU second is the per-core rate compared.
struct Clock {
  using time_point = double;
  static double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
};
double seconds_since(Clock::time_point t0) { return Clock::now() - t0; }

struct Ray {
  glm::vec3 o, d;
};

// Incoherent rays: origins on a sphere of radius 2R around c, aimed at random points inside the
// ball of radius R (every ray meets the object's bounding sphere).
std::vector<Ray> incoherent_rays(int n, const glm::dvec3& c, double R, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    glm::dvec3 a(g(rng), g(rng), g(rng)), b(g(rng), g(rng), g(rng));
    a = glm::normalize(a) * (2.0 * R);
    b = glm::normalize(b) * (R * std::cbrt(u(rng)));
    r.o = glm::vec3(c + a);
    r.d = glm::vec3(glm::normalize(b - a));
  }
  return rays;
}

void set_ray(RTCRayHit& rh, const Ray& r) {
  rh.ray.org_x = r.o.x;
  rh.ray.org_y = r.o.y;
  rh.ray.org_z = r.o.z;
  rh.ray.dir_x = r.d.x;
  rh.ray.dir_y = r.d.y;
  rh.ray.dir_z = r.d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = INFINITY;
  rh.ray.time = 0.0f;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// Triangle mesh of a sphere: lat-long grid, `rings` × `segments` quads as 2 triangles each.
RTCGeometry sphere_mesh(RTCDevice dev, double R, int rings, int segments) {
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
  const int nv = (rings + 1) * segments;
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double th = kPi * i / rings, ph = 2 * kPi * j / segments;
      float* p = v + 3 * (i * segments + j);
      p[0] = float(R * std::sin(th) * std::cos(ph));
      p[1] = float(R * std::sin(th) * std::sin(ph));
      p[2] = float(R * std::cos(th));
    }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), 2 * rings * segments));
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const unsigned a = i * segments + j, b = i * segments + (j + 1) % segments;
      const unsigned c = a + segments, d = b + segments;
      unsigned* t = idx + 6 * (i * segments + j);
      t[0] = a, t[1] = c, t[2] = b, t[3] = b, t[4] = c, t[5] = d;
    }
  rtcCommitGeometry(g);
  return g;
}

// Triangulated lens: both caps (sagged grids) and the ledge cylinder.
RTCGeometry lens_mesh(RTCDevice dev, const LensGeometry& L, int rings, int segments) {
  std::vector<float> v;
  std::vector<unsigned> t;
  const double rho = L.aperture_radius_mm();
  auto add_cap = [&](double R, double z_vertex, bool flip) {
    const unsigned base = static_cast<unsigned>(v.size() / 3);
    for (int i = 0; i <= rings; ++i)
      for (int j = 0; j < segments; ++j) {
        const double r = rho * i / rings, ph = 2 * kPi * j / segments;
        v.insert(v.end(),
                 {float(r * std::cos(ph)), float(r * std::sin(ph)), float(z_vertex + cap_sag_mm(R, r))});
      }
    for (int i = 0; i < rings; ++i)
      for (int j = 0; j < segments; ++j) {
        const unsigned a = base + i * segments + j, b = base + i * segments + (j + 1) % segments;
        const unsigned c = a + segments, d = b + segments;
        if (flip)
          t.insert(t.end(), {a, b, c, b, d, c});
        else
          t.insert(t.end(), {a, c, b, b, c, d});
      }
    return base + rings * segments;  // first vertex of the rim
  };
  const unsigned rim0 = add_cap(L.front_radius_mm(), L.front_vertex().z, false);
  const unsigned rim1 = add_cap(L.back_radius_mm(), L.back_vertex().z, true);
  for (int j = 0; j < segments; ++j) {
    const unsigned a = rim0 + j, b = rim0 + (j + 1) % segments, c = rim1 + j, d = rim1 + (j + 1) % segments;
    t.insert(t.end(), {a, b, c, b, d, c});
  }
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                         3 * sizeof(float), v.size() / 3));
  std::copy(v.begin(), v.end(), vb);
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                            3 * sizeof(unsigned), t.size() / 3));
  std::copy(t.begin(), t.end(), ib);
  rtcCommitGeometry(g);
  return g;
}

ThroughputResult time_intersect1(const char* name, RTCScene scene, const std::vector<Ray>& rays) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  std::size_t hits = 0;
  const auto t0 = Clock::now();
  for (const Ray& r : rays) {
    RTCRayHit rh;
    set_ray(rh, r);
    rtcIntersect1(scene, &ctx, &rh);
    hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }
  const double s = seconds_since(t0);
  return {name, rays.size() / s, double(rays.size()), s,
          std::to_string(100.0 * hits / rays.size()).substr(0, 5) + " % hit"};
}

template <int N, class RayHitN>
void fill_packet(RayHitN& p, const Ray* r, int valid[N]) {
  for (int i = 0; i < N; ++i) {
    valid[i] = -1;
    p.ray.org_x[i] = r[i].o.x;
    p.ray.org_y[i] = r[i].o.y;
    p.ray.org_z[i] = r[i].o.z;
    p.ray.dir_x[i] = r[i].d.x;
    p.ray.dir_y[i] = r[i].d.y;
    p.ray.dir_z[i] = r[i].d.z;
    p.ray.tnear[i] = 0.0f;
    p.ray.tfar[i] = INFINITY;
    p.ray.time[i] = 0.0f;
    p.ray.mask[i] = ~0u;
    p.ray.id[i] = 0;
    p.ray.flags[i] = 0;
    p.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    p.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
}

template <int N, class RayHitN, class Fn>
ThroughputResult time_packets(const std::string& name, RTCScene scene, const std::vector<Ray>& rays,
                              Fn intersect) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  alignas(64) RayHitN p;
  alignas(64) int valid[N];
  std::size_t hits = 0;
  const std::size_t n = rays.size() / N * N;
  const auto t0 = Clock::now();
  for (std::size_t k = 0; k < n; k += N) {
    fill_packet<N>(p, &rays[k], valid);
    intersect(valid, scene, &ctx, &p);
    for (int i = 0; i < N; ++i) hits += p.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
  }
  const double s = seconds_since(t0);
  return {name, n / s, double(n), s, std::to_string(100.0 * hits / n).substr(0, 5) + " % hit"};
}

}  // namespace

std::vector<ThroughputResult> measure_lens_throughput(int n) {
  std::vector<ThroughputResult> out;
  std::mt19937_64 rng(12345);
  LensSpec spec = load_lens_spec(asset_dir() + "/lenses/paper_rl425_rs43.json");
  const Lens lens(spec);
  const LensGeometry& G = lens.geometry();

  {  // SML, dT = 3: rays from a disk below the lens aimed at random points of the front cap's
     // aperture, each with a random linear polarization and a wavelength drawn from the paper's 81
     // uniform ones (380–780 nm in 5 nm steps), as the renderer's spectral passes use them. The
     // optical constants are looked up once per wavelength inside the timed part (as the
     // renderer's lens models do per wavelength), not per ray.
    const int m = std::max(1000, n / 4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<PolarizedRay> in(m);
    const double rho = G.aperture_radius_mm();
    for (PolarizedRay& r : in) {
      const double a = 2 * kPi * u(rng), s = rho * std::sqrt(u(rng));
      const double b = 2 * kPi * u(rng), q = 0.95 * rho * std::sqrt(u(rng));
      r.origin = G.front_vertex() + glm::dvec3(s * std::cos(a), s * std::sin(a), -10.0);
      const glm::dvec3 target = G.front_vertex() + glm::dvec3(q * std::cos(b), q * std::sin(b), 0.0);
      r.dir = glm::normalize(target - r.origin);
      glm::dvec3 ta = glm::normalize(glm::cross(r.dir, glm::dvec3(0.3, 0.5, 0.8)));
      const glm::dvec3 tb = glm::cross(r.dir, ta);
      const double phi = 2 * kPi * u(rng);
      r.pol = std::cos(phi) * ta + std::sin(phi) * tb;
      r.wavelength_nm = 380.0 + 5.0 * std::min(80, int(81.0 * u(rng)));
    }
    LensTraceOptions opt;
    opt.max_depth = 3;
    LensBundle bundle;
    std::size_t produced = 0;
    const auto t0 = Clock::now();
    LensMedia media[81];
    for (int i = 0; i < 81; ++i) media[i] = lens.media(380.0 + 5.0 * i);
    for (const PolarizedRay& r : in) {
      bundle.clear();
      trace_lens(G, media[int(std::lround((r.wavelength_nm - 380.0) / 5.0))], r, opt, bundle);
      produced += bundle.rays.size();
    }
    const double s = seconds_since(t0);
    out.push_back({"SML trace_lens dT=3 (polarized, spectral)", m / s, double(m), s,
                   std::to_string(double(produced) / m).substr(0, 4) + " outgoing rays per input"});
  }

  RTCDevice dev = rtcNewDevice("threads=1");
  {  // The lens as Embree user geometry (double-precision SML intersection inside Embree).
    RTCScene sc = rtcNewScene(dev);
    attach_lens(dev, sc, G);
    rtcCommitScene(sc);
    const auto rays = incoherent_rays(n, G.center(), G.size_mm(), rng);
    out.push_back(time_intersect1("Embree rtcIntersect1, lens as user geometry", sc, rays));
    rtcReleaseScene(sc);
  }
  {  // The lens triangulated (64 rings × 256 segments per cap).
    RTCScene sc = rtcNewScene(dev);
    RTCGeometry g = lens_mesh(dev, G, 64, 256);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(sc);
    const auto rays = incoherent_rays(n, G.center(), G.size_mm(), rng);
    out.push_back(time_intersect1("Embree rtcIntersect1, lens triangulated (33k tris)", sc, rays));
    rtcReleaseScene(sc);
  }
  {  // 262 144-triangle sphere.
    RTCScene sc = rtcNewScene(dev);
    RTCGeometry g = sphere_mesh(dev, 1.0, 256, 512);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(sc);
    const auto rays = incoherent_rays(n, glm::dvec3(0.0), 1.0, rng);
    out.push_back(time_intersect1("Embree rtcIntersect1, sphere 262k tris", sc, rays));
    if (rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED))
      out.push_back(time_packets<4, RTCRayHit4>(
          "Embree rtcIntersect4, sphere 262k tris", sc, rays,
          [](int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit4* p) { rtcIntersect4(v, s, c, p); }));
    if (rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED))
      out.push_back(time_packets<8, RTCRayHit8>(
          "Embree rtcIntersect8, sphere 262k tris", sc, rays,
          [](int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit8* p) { rtcIntersect8(v, s, c, p); }));
    if (rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED))
      out.push_back(time_packets<16, RTCRayHit16>(
          "Embree rtcIntersect16, sphere 262k tris", sc, rays,
          [](int* v, RTCScene s, RTCIntersectContext* c, RTCRayHit16* p) { rtcIntersect16(v, s, c, p); }));
    rtcReleaseScene(sc);
  }
  rtcReleaseDevice(dev);
  return out;
}

}  // namespace pmsim
