#pragma once
// The specimen's response to polarized light, and the instrument applied to it (issue 21).
//
// Everything between the polarizer and the accessory slot is linear in the field, and the
// condenser's cone and the objective's pupil are circles about the axis: so what a refracting
// specimen does to light is, per image point and wavelength, a Mueller matrix M summed
// incoherently over the condenser's directions and the paths' branches (core/optics/mueller.h),
// and turning the stage by θ is the same as turning the polarizer, the analyzer and the accessory
// by −θ and the image by θ. The response is M on a grid in the specimen's frame, traced once
// (core/specimen/forward_response.h); the instrument — stage angle, polarizer, analyzer in/out and
// its angle, accessory and wedge position — is applied to it on every frame by compose_response,
// a few multiply-adds a pixel:
//   XYZ = Σ_b W_b · ½ s_Aᵀ · C(δ_b) · M_b · t_P
// with t_P, s_A the polarizer's and analyzer's Stokes vectors and C the accessory's Mueller
// matrix, all turned into the specimen's frame by −θ (analyzer out: s = (1, 0, 0, 0), the whole
// intensity). Derivation, sources and where it does not hold: docs/physics.md.
//
// Storage (the choice and its measured error: docs/response.md): M at the reference wavelength
// (555 nm) at every grid point, and each band's difference M_b − M_ref on the chroma subgrid (every
// `chroma_period`-th point, read between by luminance-guided upsampling), as the forward renderer
// resolves colour; without an accessory the bands are summed once into colour-weighted blocks, so
// a frame reads 12 + 36/P² numbers a pixel. An accessory's retardance spectrum enters through
// three weighted sums per band (C(δ) = C0 + cos δ·C1 + sin δ·C2), formed once per accessory
// setting.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/microscope/scene.h"
#include "core/optics/mueller.h"
#include "core/render/render_image.h"
#include "core/spectrum/spectral_bands.h"

namespace pmsim {

// The settings applied to a response every frame: what may change without tracing again.
struct InstrumentSettings {
  double stage_rad = 0.0;      // stage_deg
  double polarizer_rad = 0.0;  // polarizer_deg
  bool analyzer_in = true;     // analyzer
  double analyzer_rad = 0.5 * 3.14159265358979323846;  // analyzer_deg
  Compensator compensator = Compensator::None;         // compensator
  double compensator_position = 0.0;                   // compensator_position
};
InstrumentSettings instrument_settings(const Scene& scene);

// What a response covers: the image's own field at the frame's stage angle (a single image), or
// the disc the field sweeps as the stage turns (an interactive view, a stage sweep).
enum class ResponseCoverage { Field, Disc };

// A developed response (immutable once made: a UI composes from it while the tracer goes on).
struct SpecimenResponse {
  // The image it is composed into: width × height pixels of um_per_px, centred on centre_um.
  int image_width = 0, image_height = 0;
  double um_per_px = 1.0;
  glm::dvec2 centre_um{0.0};
  // The grid: nx × ny points of um_per_px in the image frame at stage frame_stage_rad, centred on
  // centre_um (grid point (i, j) at image offset (i − (nx − 1)/2, (ny − 1)/2 − j)·grid_um, x east);
  // Field: nx = image_width, ny = image_height (the image's pixels at that angle); Disc: a square
  // holding the circle through the image's corners.
  int nx = 0, ny = 0;
  double grid_um = 1.0;  // the grid's spacing (um_per_px; a preview's grid is coarser)
  double frame_stage_rad = 0.0;
  ResponseCoverage coverage = ResponseCoverage::Field;
  // Chroma subgrid: node (I, J) at grid point (I·P, J·P), P = chroma_period.
  int chroma_period = 4, cnx = 0, cny = 0;
  SpectralBands bands;            // count() = 1 when monochromatic
  Illuminant illuminant = Illuminant::D65;
  double single_wavelength_nm = 0.0;  // > 0: monochromatic (the grey of relative intensity)
  glm::dvec3 white{1.0};          // XYZ of the illuminant's white (Y = 1)
  std::vector<float> ref;         // nx·ny × 12: M at the reference λ (mean over passes)
  std::vector<float> delta;       // cnx·cny × bands × 12: M_b − M_ref on the subgrid
  std::vector<float> delta_xyz;   // cnx·cny × 3 × 12: Σ_b W_b (M_b − M_ref), for X, Y, Z
  // Progress (as RenderImage's).
  int passes = 0;
  double samples_per_pixel = 0.0;
  double time_ms = 0.0;
  std::string model_report;
};

// The colour nodes' reconstruction between them (compose_response: joint bilateral upsampling
// guided by the reference's luminance Y, each node's colour scaled by the luminance's ratio;
// docs/response.md, "Where its error comes from" and "Measured"): the range kernel's width σ in
// the guide's relative difference (g_p − g_n)/(g_p + g_n + ε), its floor ε and the ratio's floor
// ε_r (XYZ of a white Y = 1), chosen on the bench's granite at 128² (σ 0.05–0.4 and ε_r
// 0.01–0.02 measured).
inline constexpr double kChromaGuideSigma = 0.1, kChromaGuideEps = 0.01, kChromaRatioEps = 0.02;

// The image at `instrument`: XYZ and linear sRGB, as a fresh render at those settings would give
// (within the cubic resampling of the grid, and the colour nodes' other places, when the stage
// differs from frame_stage_rad).
// Progress fields (passes, samples_per_pixel, time_ms, model_report) are the response's.
RenderImage compose_response(const SpecimenResponse& response, const InstrumentSettings& instrument);

// The mean CIEDE2000 between two responses composed at `instrument` (the split-half estimate
// when they are a render's even and odd passes), over at most 65536 pixels.
double response_difference_de2000(const SpecimenResponse& a, const SpecimenResponse& b,
                                  const InstrumentSettings& instrument);

}  // namespace pmsim
