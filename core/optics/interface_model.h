#pragma once
// How a ray tracer models an interface between two media, shared by the microscope (scene key
// optics.schlick), the SML lens tracer and the 3-D scenes (render.fresnel, render.tir).

namespace pmsim {

enum class FresnelModel {
  Exact,    // Fresnel amplitudes (fresnel.h)
  Schlick,  // APPROXIMATE: Schlick reflectance, polarization-blind (schlick.h)
};

// What happens to totally internally reflected light (the paper's SML modes, §7).
enum class TirMode {
  Stop,   // report a Tir event (intensity arriving) and stop that branch (mode 1)
  Split,  // continue the E⊥ and E∥ parts as two linear rays with their δ (mode 2, TIR_callback)
};

}  // namespace pmsim
