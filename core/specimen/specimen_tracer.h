#pragma once
// One ray traced backward from the objective down through a SpecimenScene: Snell refraction and
// Fresnel transmission (core/optics/interaction.h, the polarized G of the lens model) at every
// interface, total internal reflection followed, until the ray leaves the slide into the air
// below, where the condenser's light is looked up.
//
// Backward, one path: at each interface the ray goes on along the refracted branch with the
// Fresnel power T of its linear vibration; the reflected part R = 1 − T is counted and dropped.
// It heads back up toward the objective side, where a transmitted-light microscope has no source
// (light returning down after two reflections is O(R²) ≈ 2e-3 of it at the glass–air faces, a
// uniform veil neglected here). Under TIR the reflected branch is the path (its two linear parts
// recombined in intensity). The vibration carried is the polarizer's direction projected ⟂ the
// ray (plane light); by the Stokes reciprocity of the Fresnel powers the path's throughput is the
// one light travelling it forward would have.
#include <cstdint>

#include <glm/vec3.hpp>

#include "core/optics/polarized_ray.h"
#include "core/specimen/specimen_scene.h"

namespace pmsim {

// What the interfaces did to the traced intensity (a test's energy bookkeeping).
struct InterfaceCounters {
  std::uint64_t paths = 0;                       // rays traced
  // Fresnel events, of which TIR; paths stopped at the interface limit (trapped by repeated TIR
  // inside a fragment: dark, the light they stand for leaves after many more reflections).
  std::uint64_t events = 0, tir = 0, lost = 0;
  double incident = 0.0, reflected = 0.0, transmitted = 0.0;
  double max_defect = 0.0;  // max over events of |incident − reflected − transmitted| / incident
  // Power dropped by the polarization-exact tracer's branch cap (core/specimen/jones_path.h).
  double capped_power = 0.0;
  void add(const InterfaceCounters& o);
};

struct SpecimenPath {
  double throughput = 0.0;   // intensity reaching the air below the slide (input intensity 1)
  glm::dvec3 exit_dir{0.0};  // direction there (pointing down; light arrives along −exit_dir)
  bool left_below = false;   // false: the ray left sideways or upward, or hit the depth limit
  int interfaces = 0;
};

// `ray` starts in the air above the cover glass and points down; ray.pol is the vibration
// (⟂ dir), ray.wavelength_nm the λ. At most `max_interfaces` Fresnel events.
SpecimenPath trace_specimen(const SpecimenScene& scene, PolarizedRay ray, InterfaceCounters* counters = nullptr,
                            int max_interfaces = 64);

}  // namespace pmsim
