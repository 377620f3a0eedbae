#pragma once
// The software model of a lens (SML, paper §7): one linearly polarized ray in, the bundle of
// linearly polarized rays that leave the lens out, plus the reported special cases (TIR, ledge,
// depth limit, miss) and the absorbed intensity, so that
//     Σ rays.intensity + Σ events.intensity + absorbed + filtered = incident   (to ~1e-15 rel.)
//
// Depth: an outgoing ray's depth is the number of internal reflections before it left; the
// reflection at the entry point P1 is an outgoing ray of depth 0. Rays up to depth dT are output;
// the part reflected internally where a depth-dT ray leaves is a DepthLimit event (depth dT+1,
// the depth it would have had). Optical path: input O_p + n·S inside from P1 to the exit point
// (the application owns the path before P1); δ: input δ + the TIR phases met; ch passes through.
//
// Forward and backward tracing (paper §7). The transformation G is the same both ways: Fresnel
// power coefficients, Beer–Lambert and the ray paths are reciprocal (Stokes relations), so a
// tree traced from the eye has the same geometry and throughputs as light travelling it in
// reverse. What differs:
//  * Forward: the input ray is light from a source with its polarization; the bundle is the light
//    leaving the lens. The application's `keep` filter drops rays that cannot reach the receiver
//    (e.g. in a polariscope, rays going back toward the source, paper §7).
//  * Backward, tree-construction pass: the input ray comes from the eye and carries only λ (its
//    pol is ignored). It is traced as natural light — two incoherent orthogonal linear halves
//    of intensity I/2 (paper §5) — so each path appears twice, and the pair's intensities sum to
//    the path's throughput for unpolarized light. The `keep` filter then drops rays that cannot
//    reach the source side. The energy-collection pass is trace_lens_return(): light found along
//    an outgoing ray is sent back through the lens with its own polarization and G applied at the
//    same nodes in reverse order.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/lens/lens.h"
#include "core/optics/interaction.h"
#include "core/optics/interface_model.h"  // FresnelModel, TirMode
#include "core/optics/polarized_ray.h"

namespace pmsim {

enum class LedgeMode {
  Stop,      // report a Ledge event and stop
  Callback,  // also hand the ray arriving at the ledge to ledge_callback (then stop)
};
enum class TraceDirection { Forward, Backward };

struct LensTraceOptions {
  int max_depth = 3;  // dT
  TirMode tir = TirMode::Stop;
  LedgeMode ledge = LedgeMode::Stop;
  TraceDirection direction = TraceDirection::Forward;
  FresnelModel fresnel = FresnelModel::Exact;
  // Split mode: called with the one or two linear rays leaving a TIR point (before they go on).
  std::function<void(std::span<const PolarizedRay>)> tir_callback;
  // Callback mode: the ray arriving at the ledge (origin = hit point, attenuated intensity).
  std::function<void(const PolarizedRay&)> ledge_callback;
  // Application filter: return false to drop an outgoing ray (its intensity goes to `filtered`).
  std::function<bool(const PolarizedRay&)> keep;
  // Upper bound on rays created inside the lens per call (split TIR doubles per bounce); what
  // is not traced becomes DepthLimit events and sets LensBundle::ray_limit_reached.
  int max_internal_rays = 1 << 16;
};

struct LensEvent {
  enum class Type : std::uint8_t { Tir, Ledge, DepthLimit, Miss };
  Type type = Type::Miss;
  int depth = 0;           // depth of the ray arriving (DepthLimit: of the untraced part)
  double intensity = 0.0;  // intensity arriving at `point`
  glm::dvec3 point{0.0};   // Miss: the ray origin
};
const char* to_string(LensEvent::Type t);  // "tir", "ledge", "depth_limit", "miss"

struct LensBundle {
  std::vector<PolarizedRay> rays;  // outgoing, each linearly polarized; origin on the lens
  std::vector<LensEvent> events;
  double absorbed = 0.0;  // Beer–Lambert loss inside the glass
  double filtered = 0.0;  // outgoing intensity dropped by LensTraceOptions::keep
  double incident = 0.0;  // sum of the input intensities traced into this bundle
  bool ray_limit_reached = false;

  void clear() {
    rays.clear();
    events.clear();
    absorbed = filtered = incident = 0.0;
    ray_limit_reached = false;
  }
  double ray_intensity() const;
  double event_intensity() const;
  // incident − (rays + events + absorbed + filtered); ~1e-16·incident per interaction.
  double energy_defect() const;
};

// Trace one ray through one lens. in.origin must lie outside the lens (pass the ray as it was
// before it reached the lens, not an Embree hit point on it); an origin strictly inside the glass
// is traced from there without an entry interaction. in.pol is re-orthonormalized to in.dir.
// If the outside medium is denser and P1 totally reflects, the two linear parts are outgoing
// depth-0 rays (they never enter the glass), not a Tir event. The appending overload adds to `out` without
// clearing it (reuse one bundle across calls: no allocation once its vectors have grown).
LensBundle trace_lens(const Lens& lens, const PolarizedRay& in, const LensTraceOptions& opt);
void trace_lens(const Lens& lens, const PolarizedRay& in, const LensTraceOptions& opt, LensBundle& out);
// Same with the optical constants given directly (no material library needed).
void trace_lens(const LensGeometry& lens, const LensMedia& media, const PolarizedRay& in,
                const LensTraceOptions& opt, LensBundle& out);

// Backward tracing, energy-collection pass. `eye_ray` is the ray given to the tree pass,
// `outgoing` one of the rays it returned, `light` the light found arriving along −outgoing.dir
// (its origin, dir are ignored; pol must be ⟂ outgoing.dir). Light is traced through the lens
// forward, and the rays leaving along −eye_ray.dir (within 1e-9 rad) with depth outgoing.depth are
// appended to `out` (other branches count as `filtered`): the light reaching the eye via that path.
void trace_lens_return(const LensGeometry& lens, const LensMedia& media, const PolarizedRay& eye_ray,
                       const PolarizedRay& outgoing, const PolarizedRay& light, const LensTraceOptions& opt,
                       LensBundle& out);

}  // namespace pmsim
