#include "core/lens/lens_tracer.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "core/optics/beer_lambert.h"
#include "core/optics/polarization_frame.h"

namespace pmsim {

const char* to_string(LensEvent::Type t) {
  switch (t) {
    case LensEvent::Type::Tir:
      return "tir";
    case LensEvent::Type::Ledge:
      return "ledge";
    case LensEvent::Type::DepthLimit:
      return "depth_limit";
    case LensEvent::Type::Miss:
      return "miss";
  }
  return "?";
}

double LensBundle::ray_intensity() const {
  double s = 0.0;
  for (const PolarizedRay& r : rays) s += r.intensity;
  return s;
}
double LensBundle::event_intensity() const {
  double s = 0.0;
  for (const LensEvent& e : events) s += e.intensity;
  return s;
}
double LensBundle::energy_defect() const {
  return incident - (ray_intensity() + event_intensity() + absorbed + filtered);
}

namespace {

struct Node {
  PolarizedRay ray;  // inside the glass, origin on surface `from` (or anywhere if None)
  LensSurface from;
};

constexpr double kInf = std::numeric_limits<double>::infinity();

void emit(const PolarizedRay& r, const LensTraceOptions& opt, LensBundle& out) {
  if (opt.keep && !opt.keep(r)) {
    out.filtered += r.intensity;
    return;
  }
  out.rays.push_back(r);
}

void event(LensBundle& out, LensEvent::Type type, int depth, double intensity, const glm::dvec3& p) {
  out.events.push_back({type, depth, intensity, p});
}

// True when interact() at an exit point would report TIR and the trace would stop there with a
// Tir event of the ray's whole intensity: then the event is written without interact(), whose TIR
// branch computes the phases δ⊥, δ∥ (atan2), turns them into r_s, r_p (sincos) and back (arg →
// atan2) for reflected rays that Stop mode discards. The test is interact()'s own: the same
// cos θi = min(1, |d·N|), η = n_t/n_i and fresnel.h's cos²θt < 0 (Exact model only; Schlick has
// its own). interact() would emit the event only if a reflected part has I·a² > 0; with a unit v_p
// ⟂ d, a_s² + a_p² = 1 to rounding, so one part is ≥ I/2 > 0 whenever I ≥ 1e-300; rays fainter than
// that take the full path.
bool stops_at_tir(const LensTraceOptions& opt, const PolarizedRay& r, const glm::dvec3& normal,
                  const LensMedia& m) {
  if (opt.tir != TirMode::Stop || opt.fresnel != FresnelModel::Exact || !(r.intensity >= 1e-300)) return false;
  const double cos_i = std::min(1.0, std::abs(glm::dot(r.dir, normal)));
  return snell_cos_t2(cos_i, m.n_medium / m.n_glass) < 0.0;
}

// One linearly polarized ray (pol already ⟂ dir, unit) through the lens.
void trace_one(const LensGeometry& g, const LensMedia& m, const PolarizedRay& in0,
               const LensTraceOptions& opt, LensBundle& out) {
  // The stack is reused per thread: no allocation per call once it has grown. Depth-first, each
  // node pushes at most two children, so it holds at most ~dT + 2 nodes.
  thread_local std::vector<Node> stack;
  stack.clear();
  const int dT = std::max(0, opt.max_depth);
  int internal_rays = 0;
  InteractionResult res;

  LensHit hit;
  if (!g.intersect(in0.origin, in0.dir, kInf, LensSurface::None, hit)) {
    event(out, LensEvent::Type::Miss, 0, in0.intensity, in0.origin);
    return;
  }
  if (glm::dot(in0.dir, hit.normal) > 0.0) {
    // The origin is inside the glass: trace from there (path and absorption from the origin).
    PolarizedRay r = in0;
    r.depth = 0;
    stack.push_back({r, LensSurface::None});
  } else if (hit.surface == LensSurface::Ledge) {
    PolarizedRay at = in0;
    at.origin = hit.point;
    at.depth = 0;
    event(out, LensEvent::Type::Ledge, 0, in0.intensity, hit.point);
    if (opt.ledge == LedgeMode::Callback && opt.ledge_callback) opt.ledge_callback(at);
    return;
  } else {
    // Entry point P1: G from the medium into the glass.
    interact(in0, hit.point, hit.normal, m.n_medium, m.n_glass, opt.fresnel, res);
    for (int k = 0; k < res.reflected_count; ++k) {
      res.reflected[k].depth = 0;
      emit(res.reflected[k], opt, out);
    }
    if (res.has_refracted) {
      res.refracted.depth = 0;
      stack.push_back({res.refracted, hit.surface});
      ++internal_rays;
    }
  }

  while (!stack.empty()) {
    Node node = stack.back();
    stack.pop_back();
    PolarizedRay& r = node.ray;
    if (!g.intersect(r.origin, r.dir, kInf, node.from, hit)) {
      // A closed solid always has an exit; this is a numerical leak, reported so energy balances.
      event(out, LensEvent::Type::Miss, r.depth, r.intensity, r.origin);
      continue;
    }
    // Propagation inside: O_p += n·S, I ← I·e^(−μS) (paper §6).
    const double I_after = r.intensity * beer_lambert_transmittance(m.attenuation_per_mm, hit.t);
    out.absorbed += r.intensity - I_after;
    r.intensity = I_after;
    r.optical_path_mm += optical_path_mm(m.n_glass, hit.t);

    if (hit.surface == LensSurface::Ledge) {
      event(out, LensEvent::Type::Ledge, r.depth, r.intensity, hit.point);
      if (opt.ledge == LedgeMode::Callback && opt.ledge_callback) {
        PolarizedRay at = r;
        at.origin = hit.point;
        opt.ledge_callback(at);
      }
      continue;
    }

    if (stops_at_tir(opt, r, hit.normal, m)) {
      event(out, LensEvent::Type::Tir, r.depth, r.intensity, hit.point);
      continue;
    }
    interact(r, hit.point, hit.normal, m.n_glass, m.n_medium, opt.fresnel, res);
    if (res.has_refracted) {
      res.refracted.depth = r.depth;
      emit(res.refracted, opt, out);
    }
    if (res.reflected_count == 0) continue;
    if (res.tir && opt.tir == TirMode::Stop) {
      event(out, LensEvent::Type::Tir, r.depth, r.intensity, hit.point);
      continue;
    }
    const int child_depth = r.depth + 1;
    for (int k = 0; k < res.reflected_count; ++k) res.reflected[k].depth = child_depth;
    if (child_depth > dT) {
      event(out, LensEvent::Type::DepthLimit, child_depth, res.reflected_intensity(), hit.point);
      continue;
    }
    if (res.tir && opt.tir_callback)
      opt.tir_callback(std::span<const PolarizedRay>(res.reflected, res.reflected_count));
    for (int k = 0; k < res.reflected_count; ++k) {
      if (internal_rays >= opt.max_internal_rays) {
        out.ray_limit_reached = true;
        event(out, LensEvent::Type::DepthLimit, child_depth, res.reflected[k].intensity, hit.point);
        continue;
      }
      ++internal_rays;
      stack.push_back({res.reflected[k], hit.surface});
    }
  }
}

}  // namespace

void trace_lens(const LensGeometry& g, const LensMedia& m, const PolarizedRay& in,
                const LensTraceOptions& opt, LensBundle& out) {
  out.incident += in.intensity;
  PolarizedRay r = in;
  r.dir = glm::normalize(in.dir);
  if (opt.direction == TraceDirection::Backward) {
    // Natural light = two incoherent orthogonal linear waves of I/2 (paper §5).
    const glm::dvec3 a = any_perpendicular(r.dir);
    r.intensity = 0.5 * in.intensity;
    r.pol = a;
    trace_one(g, m, r, opt, out);
    r.pol = glm::cross(r.dir, a);
    trace_one(g, m, r, opt, out);
    return;
  }
  // Keep v_p exactly ⟂ dir and unit so that the Fresnel split conserves energy to rounding.
  const glm::dvec3 p = in.pol - glm::dot(in.pol, r.dir) * r.dir;
  const double pl = glm::length(p);
  r.pol = pl > 0.0 ? p / pl : any_perpendicular(r.dir);
  trace_one(g, m, r, opt, out);
}

void trace_lens(const Lens& lens, const PolarizedRay& in, const LensTraceOptions& opt, LensBundle& out) {
  trace_lens(lens.geometry(), lens.media(in.wavelength_nm), in, opt, out);
}

LensBundle trace_lens(const Lens& lens, const PolarizedRay& in, const LensTraceOptions& opt) {
  LensBundle b;
  trace_lens(lens, in, opt, b);
  return b;
}

void trace_lens_return(const LensGeometry& g, const LensMedia& m, const PolarizedRay& eye_ray,
                       const PolarizedRay& outgoing, const PolarizedRay& light, const LensTraceOptions& opt,
                       LensBundle& out) {
  PolarizedRay l = light;
  l.dir = -glm::normalize(outgoing.dir);
  // Start a little outside the exit point so the entry hit is found robustly (1e-6 of the lens
  // size: far below any feature, far above rounding).
  l.origin = outgoing.origin - 1e-6 * g.size_mm() * l.dir;
  l.wavelength_nm = outgoing.wavelength_nm;
  const glm::dvec3 to_eye = -glm::normalize(eye_ray.dir);
  const int depth = outgoing.depth;
  LensTraceOptions o = opt;
  o.direction = TraceDirection::Forward;
  o.keep = [&](const PolarizedRay& r) {
    return r.depth == depth && glm::dot(r.dir, to_eye) > 0.0 &&
           glm::length(glm::cross(r.dir, to_eye)) < 1e-9 && (!opt.keep || opt.keep(r));
  };
  trace_lens(g, m, l, o, out);
}

}  // namespace pmsim
