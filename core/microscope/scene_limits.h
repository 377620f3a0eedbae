#pragma once
// The ranges a Scene's values must lie in: check_scene (scene_check.h) refuses what is outside,
// and the UI's controls, shortcuts and the file readers take their bounds from here, so that a
// slider never offers a value the scene would refuse. Each bound says why it is where it is.

namespace pmsim {

// Objective magnification: (0, 1000]; the highest dry objectives are 100–150×.
inline constexpr double kMaxMagnification = 1000.0;
// Eyepiece field numbers run from 18 mm (student eyepieces) to 26.5 mm (wide-field ones); the
// range allowed is wider, but a field number must be a positive length.
inline constexpr double kMaxFieldNumberMm = 100.0;
// The stage travel of a microscope is a few centimetres; ±1 m keeps every derived coordinate far
// from overflow while refusing typos such as 1e300.
inline constexpr double kMaxStageTravelMm = 1000.0;
// A fine-focus travel of ±1 mm holds any specimen on a slide; beyond that is a typo.
inline constexpr double kMaxFocusUm = 1000.0;
// n_D of the mounting medium or liquid: the range of the standard immersion-liquid series
// (assets/liquids/immersion_liquids.json).
inline constexpr double kMinMediumIndex = 1.40, kMaxMediumIndex = 1.80;
// A specimen up to 10 cm thick (a crystal block), far beyond any section or plate.
inline constexpr double kMaxThicknessUm = 1e5;
// Render size: each side up to 16384 pixels, the product up to kMaxRenderPixels: 8192² pixels
// already take ~3.5 GB (float RGB + XYZ and the double accumulators); 16384² would take ~13 GB.
inline constexpr int kMaxRenderSide = 16384;
inline constexpr long long kMaxRenderPixels = 8192LL * 8192LL;
// Passes and wavelengths of a render (0: until converged).
inline constexpr int kMaxSpp = 1000000;
inline constexpr int kMaxWavelengths = 4001;
// A single wavelength lies in the visible range the colour-matching functions cover.
inline constexpr double kMinSingleWavelengthNm = 380.0, kMaxSingleWavelengthNm = 780.0;
// The photographer's exposure (render.exposure_ev): ±10 stops (a factor of ~1000 either way)
// covers every image pmsim makes, from a near-extinct section to the brightest fringe.
inline constexpr double kMinExposureEv = -10.0, kMaxExposureEv = 10.0;
// Lens reflections traced (optics.lens_depth): a bound on the ghost recursion; a ghost of d
// reflections carries about R^d of the light, 0.04^10 ≈ 10⁻¹⁴ at uncoated glass (Fresnel, normal
// incidence, n = 1.5).
inline constexpr int kMaxLensDepth = 10;

}  // namespace pmsim
