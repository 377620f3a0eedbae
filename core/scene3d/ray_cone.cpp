#include "core/scene3d/ray_cone.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "core/lens/lens_tracer.h"

namespace pmsim {

LensSpec ray_cone_lens(const RayConeSetup& s) {
  LensSpec spec;
  spec.glass = s.glass;
  spec.medium = "air";
  spec.center = glm::dvec3(0.0);
  spec.axis = glm::dvec3(0.0, 0.0, 1.0);
  spec.radius_mm = s.lens_radius_mm;
  spec.ledge_mm = s.ledge_mm;
  // lens.h sign convention: a radius is positive when its centre of curvature lies on the +axis
  // side. "front" is the cap at −z (away from the camera), "back" the cap at +z.
  const double R = s.sphere_radius_mm;
  if (s.form == RayConeSetup::Form::Biconvex) {
    spec.front_radius_mm = R;
    spec.back_radius_mm = -R;
  } else if (s.curved_side_to_camera) {
    spec.front_radius_mm = 0.0;
    spec.back_radius_mm = -R;
  } else {
    spec.front_radius_mm = R;
    spec.back_radius_mm = 0.0;
  }
  return spec;
}

double ray_cone_reference_z(const RayConeSetup& s) {
  const LensSpec spec = ray_cone_lens(s);
  const double t = *spec.ledge_mm + cap_sag_mm(spec.front_radius_mm, s.lens_radius_mm) -
                   cap_sag_mm(spec.back_radius_mm, s.lens_radius_mm);
  const double z_vertex = 0.5 * t;  // camera-side vertex (centre = midpoint of the vertices)
  if (s.reference == RayConeSetup::Reference::CameraSideVertex) return z_vertex;
  return z_vertex + cap_sag_mm(spec.back_radius_mm, s.lens_radius_mm);  // rim of the +z cap
}

RayConePath trace_ray_cone_path(const Lens& lens, const RayConeSetup& s, double r_mm) {
  const double zO = ray_cone_reference_z(s);
  PolarizedRay in;
  if (std::isinf(s.camera_height_mm)) {
    // Camera at infinity: rays parallel to the axis, started above the lens.
    in.origin = glm::dvec3(r_mm, 0.0, zO + 2.0 * lens.geometry().size_mm() + 1.0);
    in.dir = glm::dvec3(0.0, 0.0, -1.0);
  } else {
    in.origin = glm::dvec3(0.0, 0.0, zO + s.camera_height_mm);
    in.dir = glm::normalize(glm::dvec3(r_mm, 0.0, zO) - in.origin);
  }
  in.wavelength_nm = s.wavelength_nm;
  LensTraceOptions opt;
  opt.max_depth = s.max_depth;
  // Split: TIR does not end the path (it is not a ledge); both parts follow the same geometry.
  opt.tir = TirMode::Split;
  opt.ledge = LedgeMode::Stop;
  opt.direction = TraceDirection::Forward;
  const LensMedia media = lens.media(s.wavelength_nm);
  RayConePath p;
  p.clean = true;
  // Natural light: the halves ⟂ and ∥ to the meridional (x–z) plane, I0/2 each. In this plane
  // they stay ⟂ and ∥ at every node, so no other state can appear.
  const glm::dvec3 s_pol(0.0, 1.0, 0.0);
  const glm::dvec3 p_pol = glm::normalize(glm::cross(in.dir, s_pol));
  LensBundle b;
  for (const glm::dvec3& pol : {s_pol, p_pol}) {
    PolarizedRay r = in;
    r.pol = pol;
    r.intensity = 0.5;
    b.clear();
    trace_lens(lens.geometry(), media, r, opt, b);
    for (const LensEvent& e : b.events) {
      // A ledge reached by an inner ray of depth ≤ 4 lies on the path P1 … P6 (the ray from
      // P_k to P_(k+1) has depth k − 1); missing the lens disqualifies the ray as well.
      if ((e.type == LensEvent::Type::Ledge && e.depth <= 4) || e.type == LensEvent::Type::Miss)
        p.clean = false;
    }
    if (s.tir_stops_intensity) {
      LensTraceOptions stop = opt;
      stop.tir = TirMode::Stop;
      b.clear();
      trace_lens(lens.geometry(), media, r, stop, b);
    }
    for (const PolarizedRay& o : b.rays) {
      if (o.dir.z >= 0.0) continue;  // leaves toward the camera: the reflection at P1, Out3, Out5
      if (o.depth == 0) p.I2 += o.intensity;
      if (o.depth == 2) p.I4 += o.intensity;
      if (o.depth == 4) p.I6 += o.intensity;
    }
  }
  return p;
}

namespace {

RayConeResult scan(const RayConeSetup& s, int samples, double eta_limit) {
  const Lens lens(ray_cone_lens(s));
  RayConeResult res;
  res.samples = samples;
  const double RL = s.lens_radius_mm;
  bool open = true;
  for (int k = 0; k < samples; ++k) {
    const double r = RL * k / (samples - 1);
    if (eta_limit >= 0.0 && r > eta_limit * RL * (1.0 + 1e-12)) break;
    const RayConePath p = trace_ray_cone_path(lens, s, r);
    if (eta_limit < 0.0) {
      if (!p.clean) {
        open = false;
        break;
      }
      res.eta = r / RL;
    } else if (!p.clean) {
      continue;
    }
    if (!(p.I2 > 0.0)) continue;
    res.eta4_max = std::max(res.eta4_max, p.eta4());
    res.eta6_max = std::max(res.eta6_max, p.eta6());
  }
  if (eta_limit >= 0.0) res.eta = eta_limit;
  (void)open;
  return res;
}

}  // namespace

RayConeResult ray_cone(const RayConeSetup& s, int samples) { return scan(s, samples, -1.0); }

RayConeResult ray_cone_at(const RayConeSetup& s, double eta, int samples) { return scan(s, samples, eta); }

}  // namespace pmsim
