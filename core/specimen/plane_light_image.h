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
// is still found. Exposure: the empty field (no fragment) of the same stack with the analyzer out
// gives Y = 1 (so between parallel polars an empty field is 1, between crossed ones 0).
//
// Polarization (core/specimen/jones_path.h): every path is traced with complex fields, split
// into a crystal's two modes and summed coherently at the polarizer. Analyzer in: the backward
// path starts with the analyzer's vibration, I = |⟨p|J|a⟩|²; analyzer out: with two orthogonal
// ones, I = Σ_a |⟨p|J|a⟩|² (the whole power behind the polarizer, exact).
//
// Spectrum: `bands` bands over 380–780 nm, each weighted by its ∫ observer × illuminant; the λ
// within a band is stratified over the passes (a pixel's λ offset in the band is a van der Corput
// sequence over the passes, rotated by a random offset per pixel, shared by every band). With the
// analyzer in, interference colours vary with λ as sin²(πΓ/λ): a band must be narrow against the
// period λ²/Γ of that oscillation where the eye still sees colour (Γ ≲ 2000 nm: λ²/Γ ≳ 120 nm
// at 500 nm; beyond that the colours fade to the high-order white, which any band width averages
// correctly), so at least kCrossedPolarBands bands (12.5 nm) are used. A pass traces 8 of them
// (every fourth in turn), so the first image costs what a plane-light pass costs.
#include <atomic>
#include <cstdint>
#include <functional>

#include <glm/vec2.hpp>

#include "core/base/units.h"
#include "core/render/render_image.h"
#include "core/spectrum/illuminant.h"
#include "core/specimen/specimen_scene.h"
#include "core/specimen/jones_path.h"
#include "core/specimen/specimen_tracer.h"

namespace pmsim {

// condenser.aperture_na = 0 stands for the diaphragm stopped down. A real iris does not close
// to a point and the lamp's field lens fills what is left with an image of a finite filament;
// strictly parallel light would light no ray of a finite aperture at all (a set of measure zero).
// 0.03 is the smallest opening of a petrographic condenser's iris (about 1 mm in a condenser of
// ~17 mm focal length: sin θ ≈ 0.5/17).
constexpr double kStoppedDownApertureNa = 0.03;

// Bands with the analyzer in (see above): 12.5 nm, a tenth of the period of sin²(πΓ/λ) at the
// upper end of the second order.
constexpr int kCrossedPolarBands = 32;

struct PlaneLightOptions {
  int width = 256, height = 256;
  glm::dvec2 centre_um{0.0};        // specimen point under the image centre
  double um_per_px = 1.0;
  double stage_rad = 0.0;           // the specimen turned by this about z (counter-clockwise)
  double focus_um = 0.0;
  double objective_na = 0.25;
  double condenser_aperture_na = 0.0;  // 0: kStoppedDownApertureNa
  double polarizer_rad = 0.0;       // vibration direction of the polarizer, from +x
  bool analyzer_in = false;         // crossed (or any) polars: the analyzer's vibration is traced
  double analyzer_rad = kPi / 2;    // the analyzer's vibration direction, from +x (π/2: N–S)
  // Plane light with the one-vibration tracer of specimen_tracer.h instead of the polarization-
  // exact one (analyzer out only): kept to compare the two in tests.
  bool scalar_tracer = false;
  Illuminant illuminant = Illuminant::D65;
  double single_wavelength_nm = 0.0;  // > 0: monochromatic (R = G = B = relative intensity)
  int bands = 8;                    // spectral bands over 380–780 nm (white light; analyzer in: ≥ kCrossedPolarBands)
  int spp = 64;                     // samples per pixel in all (rounded up to whole passes)
  std::uint64_t seed = 1;
};

// Renders pass by pass (each pass one inner and one annulus sample per pixel for up to 8 bands);
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
