#pragma once
// Whitted-style backward ray tracer (Whitted 1980) over a Scene3dWorld, carrying the paper's
// payload: at glass and lens surfaces the camera ray becomes linearly polarized rays (natural
// light = two incoherent orthogonal linear halves, paper §5) transformed by G (Fresnel or
// Schlick), lenses are traced by the SML (trace_lens) and every ray of its bundle is followed.
// Diffuse surfaces are Lambertian and depolarize; they are lit directly by point and area lights
// (shadow rays), as in Whitted's model. Glass bodies and lenses stand in air (n = 1) and do not
// block shadow rays (see Scene3dWorld::opaque_between).
//
// Backward tracing of polarization: for real Fresnel amplitudes the Jones matrix of a path
// traversed backward is the transpose of the forward one (Stokes reciprocity), so a linear state
// v traced from the eye ends with intensity |J v|², and the eye's response to natural light of
// radiance L arriving along the path is ½·|J v|²·L summed over the eye's states (both halves for
// a bare camera, the filter axis alone behind a polarizer).
//
// Spectral mode: N wavelengths travel together until the first dispersive interface, where the
// tree splits into one sub-tree per wavelength (the paper's nSp-times more trees, but only where
// glass is seen). RGB mode: three channels and one refractive index, n(587.56 nm).
#include <glm/vec3.hpp>
#include <vector>

#include "core/lens/lens_tracer.h"
#include "core/scene3d/scene3d_world.h"

namespace pmsim {

class WhittedTracer {
 public:
  static constexpr int kMaxChannels = 81;
  explicit WhittedTracer(const Scene3dWorld& world);

  // Linear sRGB arriving along a ray from the eye. filter_axis: transmission axis of an ideal
  // linear polarizer in front of the eye (unit, ⟂ dir), or nullptr for no filter.
  glm::dvec3 trace(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3* filter_axis) const;

  int channels() const { return static_cast<int>(nm_.size()); }
  const std::vector<double>& wavelengths_nm() const { return nm_; }
  // Linear sRGB the renderer uses for a diffuse colour (RGB mode: the Smits spectrum seen
  // under D65 and projected back, so that RGB and spectral renders agree away from glass).
  glm::dvec3 effective_rgb(const glm::dvec3& rgb) const;

 private:
  using Acc = double[kMaxChannels];
  void radiance(const glm::dvec3& origin, const glm::dvec3& dir, int depth, int ch, const glm::dvec3* pol,
                double w, Acc acc) const;
  void shade(const glm::dvec3& origin, const glm::dvec3& dir, const Scene3dHit& hit, int depth, int ch,
             const glm::dvec3* pol, double w, Acc acc) const;
  void shade_diffuse(const glm::dvec3& dir, const Scene3dHit& hit, int ch, double w, Acc acc) const;
  void shade_glass(const glm::dvec3& origin, const glm::dvec3& dir, const Scene3dHit& hit, int depth, int ch,
                   const glm::dvec3& pol, double w, Acc acc) const;
  std::vector<double> spectrum_of_rgb(const glm::dvec3& rgb, Illuminant illum) const;

  const Scene3dWorld& world_;
  const Scene3dDescription& desc_;
  bool spectral_ = true;
  double eps_ = 1e-5;
  std::vector<double> nm_;                                     // per channel
  std::vector<glm::dvec3> to_rgb_;                             // channel value → linear sRGB
  std::vector<std::vector<std::vector<double>>> reflectance_;  // [material][colour][channel]
  std::vector<std::vector<double>> emission_;                  // [light][channel]
  std::vector<double> background_, ambient_;                   // [channel]
  // Optical constants per glass material / lens, [index][channel]; RGB mode: one entry per
  // channel, all at 587.56 nm.
  std::vector<std::vector<double>> glass_n_, glass_mu_;
  std::vector<std::vector<LensMedia>> lens_media_;
  LensTraceOptions lens_options_;
  FresnelModel fresnel_ = FresnelModel::Exact;
};

}  // namespace pmsim
