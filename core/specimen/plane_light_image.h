#pragma once
// Image formation in plane-polarized light through a refracting specimen, traced backward from
// each pixel (issue 12): the objective is a thin-lens camera of numerical aperture NA focused on a
// plane; for every pixel, directions within its cone through the focal-plane point are traced
// down through cover glass, liquid, fragments and slide (core/specimen/specimen_tracer.h), and a
// ray carries light only if it leaves the slide inside the condenser's cone of illumination
// (sin θ_air ≤ the aperture diaphragm's NA). A ray bent outside that cone is dark — the dark
// outline of high relief — and rays bent into it from elsewhere crowd into the Becke line.
//
// Focus: focus_um is the objective's travel, + up. At 0 the paraxial focus lies on the specimen's
// mid-plane, so the focus point in air (where the cone's rays would meet without the specimen)
// is the mid-plane seen through the cover glass and the liquid at their apparent depths,
// z_air = z_cover_top − t_cover/n_glass − (z_cover_bottom − z_mid)/n_liquid (n at 589 nm), plus
// focus_um: raising the objective raises that point by the same amount.
//
// Aperture sampling: sin θ = NA·√u (uniform over the pupil, cos-weighted, as the irradiance of
// a Lambertian pupil); stratified into the disk sin θ ≤ NA_c (the rays that would be lit without
// the specimen) and the annulus outside it, half the samples each, every stratum weighted by its
// pupil area, so that the empty field has almost no noise and the light bent in from the annulus
// is still found. Exposure: the empty field (no fragment) of the same stack gives Y = 1.
#include <atomic>
#include <cstdint>
#include <functional>

#include <glm/vec2.hpp>

#include "core/render/render_image.h"
#include "core/spectrum/illuminant.h"
#include "core/specimen/specimen_scene.h"
#include "core/specimen/specimen_tracer.h"

namespace pmsim {

// condenser.aperture_na = 0 stands for the diaphragm stopped down. A real iris does not close
// to a point and the lamp's field lens fills what is left with an image of a finite filament;
// strictly parallel light would light no ray of a finite aperture at all (a set of measure zero).
// 0.03 is the smallest opening of a petrographic condenser's iris (about 1 mm in a condenser of
// ~17 mm focal length: sin θ ≈ 0.5/17).
constexpr double kStoppedDownApertureNa = 0.03;

struct PlaneLightOptions {
  int width = 256, height = 256;
  glm::dvec2 centre_um{0.0};        // specimen point under the image centre
  double um_per_px = 1.0;
  double stage_rad = 0.0;           // the specimen turned by this about z (counter-clockwise)
  double focus_um = 0.0;
  double objective_na = 0.25;
  double condenser_aperture_na = 0.0;  // 0: kStoppedDownApertureNa
  double polarizer_rad = 0.0;       // vibration direction of the polarizer, from +x
  Illuminant illuminant = Illuminant::D65;
  double single_wavelength_nm = 0.0;  // > 0: monochromatic (R = G = B = relative intensity)
  int bands = 8;                    // spectral bands over 380–780 nm (white light)
  int spp = 64;                     // samples per pixel in all (rounded up to whole passes)
  std::uint64_t seed = 1;
};

// Renders pass by pass (each pass one inner and one annulus sample per band and pixel);
// `progress` sees the image after each pass. `counters` (optional) sums every Fresnel event.
// `cancel` (optional, polled every pixel row): once raised, the pass in flight is abandoned and
// the last finished pass's image is returned (converged = false), so an interactive client can
// leave a scene within a row's time instead of a whole pass's.
RenderImage render_plane_light(const SpecimenScene& scene, const PlaneLightOptions& options,
                               const std::function<void(const RenderImage&)>& progress = nullptr,
                               InterfaceCounters* counters = nullptr, const std::atomic<bool>* cancel = nullptr);

// The effective condenser NA for an aperture setting (0 → kStoppedDownApertureNa).
inline double effective_condenser_na(double aperture_na) {
  return aperture_na > 0.0 ? aperture_na : kStoppedDownApertureNa;
}

}  // namespace pmsim
