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
// the specimen) and the annulus outside it, one sample each a pass, every stratum weighted by its
// pupil area, so that the light bent in from the annulus is still found. Exposure: the empty field
// (no fragment) of the same stack with the analyzer out gives Y = 1 (so between parallel polars an
// empty field is 1, between crossed ones about 0).
//
// Where the time goes (issue 12's speed targets), and what is exact about each saving:
// - A pixel whose every ray crosses the liquid layer outside all fragments' bounding boxes sees
//   only the plane faces of the empty stack: its value is the empty field, 1, exactly, and no ray
//   is traced for it (the cone's reach in the liquid is bounded from the objective's NA).
// - The pixel point, pupil direction and wavelength jitter of pass k are a randomly shifted
//   Kronecker sequence in k (Cranley–Patterson rotation of the R-sequence, M. Roberts 2018): still
//   unbiased, but stratified over the passes instead of independent.
// - White light: each direction is traced at a fixed reference wavelength and at one band's (the
//   band cycling over the passes); a band's value is the reference's mean over all passes plus its
//   own passes' mean difference T(λ_b) − T(λ_ref) — a control variate, exact in expectation, whose
//   difference vanishes except where dispersion changes a path. Two traces a direction, not eight.
// - Split half: the even and odd passes accumulate apart; their mean CIEDE2000 is the error
//   estimate of the whole (conservative: see plane_light_image.cpp), and the render stops once it
//   is below options.tolerance_de2000.
// Where the noise is: with the diaphragm stopped down (NA_c 0.03 under an NA 0.25 objective), a
// lit annulus ray weighs (NA/NA_c)² ≈ 68 empty fields and is rare — the Becke line's light. Per-tile
// guiding of the annulus toward where lit rays had been (mixture importance sampling) was tried
// and measured no gain (mean ΔE00 5.55 vs 5.71 at 64 paths, 4.60 vs 4.41 at 256, 128² garnet):
// the lit patches are small and differ pixel to pixel. Tracing forward from the condenser's small
// cone (the "or forward, whichever converges faster") is what would remove it.
// - A preview (options.preview_factor > 1): first an image 1/factor the size, one inner-stratum
//   sample a pixel at the reference wavelength (grey), spread bilinearly over the full grid.
//
// Polarization (core/specimen/jones_path.h): every path is traced with complex fields, split
// into a crystal's two modes and summed coherently at the polarizer. Analyzer in: the backward
// path starts with the analyzer's vibration, I = |⟨p|J|a⟩|²; analyzer out: with two orthogonal
// ones, I = Σ_a |⟨p|J|a⟩|² (the whole power behind the polarizer, exact).
//
// Spectrum: `bands` bands over 380–780 nm, each weighted by its ∫ observer × illuminant; the λ
// within a band is the pass's Kronecker coordinate (stratified over the passes). With the analyzer
// in, interference colours vary with λ as sin²(πΓ/λ): a band must be narrow against the period
// λ²/Γ of that oscillation where the eye still sees colour (Γ ≲ 2000 nm: λ²/Γ ≳ 120 nm at 500 nm;
// beyond that the colours fade to the high-order white, which any band width averages correctly),
// so at least kCrossedPolarBands bands (12.5 nm) are used. A pass traces the reference wavelength
// and, as control-variate differences to it, one band (plane light) or 8 bands, one of every
// fourth in turn (analyzer in), so a pass's cost grows by the bands the colour needs, not by 32.
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
// The most bands a traced specimen takes from render.wavelengths: 128 bands of 3.1 nm hold the
// colour of retardations up to ~40 orders at a tenth of a fringe; the response's colour store,
// 48 bytes a band and chroma node, is then 0.2 GB for a 512² Disc (a 736² grid, nodes every 4).
constexpr int kMaxTracedBands = 128;

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
  int spp = 64;                     // traced paths per pixel in all (rounded up to whole passes)
  double tolerance_de2000 = 0.0;    // > 0: stop once the split-half estimate is below it
  int preview_factor = 0;           // > 1: a first image at 1/factor of the size (see above)
  // Forward renderer only (forward_plane_light.h): the period of the subgrid the bands are traced
  // from; 0 = its default (3 in plane light, 4 with the analyzer in), 1 = every point (the colour
  // at full resolution: a reference free of the default's chroma blur, at 9 or 33 traces a pixel).
  int chroma_period = 0;
  std::uint64_t seed = 1;
};

// Renders pass by pass (each pass one inner and one annulus direction per pixel, traced at the
// reference wavelength and at one band, or 8 bands with the analyzer in);
// `progress` sees the image after each pass (and the preview first, passes = 1, if asked for). `counters` (optional) sums every Fresnel event.
// `cancel` (optional, polled every pixel row): once raised, the pass in flight is abandoned and
// the last finished pass's image is returned (converged = false, stopped "cancelled"), so an interactive client can
// leave a scene within a row's time instead of a whole pass's.
RenderImage render_plane_light(const SpecimenScene& scene, const PlaneLightOptions& options,
                               const std::function<void(const RenderImage&)>& progress = nullptr,
                               InterfaceCounters* counters = nullptr, const std::atomic<bool>* cancel = nullptr);

// The plane (z, µm) in the air above the cover glass where the objective's cone converges, focused
// at focus_um: the specimen's mid-plane seen through cover glass and liquid at their apparent
// depths (n at 589.26 nm), raised by focus_um (see the top of this file).
double objective_focus_z_air_um(const SpecimenScene& scene, double focus_um);

// The effective condenser NA for an aperture setting (0 → kStoppedDownApertureNa).
inline double effective_condenser_na(double aperture_na) {
  return aperture_na > 0.0 ? aperture_na : kStoppedDownApertureNa;
}

}  // namespace pmsim
