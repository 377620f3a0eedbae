#pragma once
// The polarizing train around the sample, for one wavelength: polarizer → (sample) → compensator
// → analyzer, in the ideal-lens model where every lens maps the transverse basis of a ray
// (core/crystal/plate.h transverse_basis: a ≈ east, b ≈ north) onto the lab x, y without changing
// the polarization. The incident field is the unit vector along the polarizer, so an isotropic
// loss-free sample between parallel polars transmits exactly 1 (the exposure reference, Y = 1;
// docs/conventions.md).
#include <glm/vec2.hpp>

#include "core/microscope/compensator.h"
#include "core/microscope/scene.h"
#include "core/optics/jones.h"

namespace pmsim {

// The sample as its two eigenmodes at one wavelength and direction (fast 1, slow 2), field
// directions in the ray's transverse basis, with the retardation and its spectral slope.
struct ModalPoint {
  glm::dvec2 e1{1.0, 0.0}, e2{0.0, 1.0};
  double t1 = 1.0, t2 = 1.0;
  double gamma_nm = 0.0;    // Γ = optical path difference slow − fast
  double dgamma_dnm = 0.0;  // dΓ/dλ
};

struct TrainState {
  double wavelength_nm = 550.0;
  glm::dvec2 polarizer{1.0, 0.0};
  int outputs = 1;  // 1: analyzer in; 2: analyzer out (x and y)
  glm::dvec2 output[2]{{0.0, 1.0}, {1.0, 0.0}};
  int comp_modes = 1;  // 1: no compensator (identity); 2: fast, slow
  glm::dvec2 comp_dir[2]{{1.0, 0.0}, {0.0, 1.0}};
  double chi_rad = 0.0, dchi_dnm = 0.0;  // compensator phase 2πΓc/λ and its slope
  JonesMatrix comp_jones = JonesMatrix::identity();
};

TrainState make_train(const Scene& scene, const CompensatorPlate& comp, double wavelength_nm);

// The same train seen from a specimen turned by stage_rad (counter-clockwise, as the stage): every
// lab-fixed direction — polarizer, analyzer, the accessory's slot — turned by −stage_rad, the
// accessory's Jones matrix J as R(−θ)·J·R(θ). Lenses are figures of revolution, so a stage-0°
// specimen in this train transmits what the turned specimen does in the lab's (docs/physics.md,
// "One response, many settings").
TrainState train_in_specimen_frame(const TrainState& lab, double stage_rad);

// Transmitted intensity for a sample given by its Jones matrix (exact, at the wavelength).
double jones_transmission(const TrainState& train, const JonesMatrix& sample);
JonesVector jones_output(const TrainState& train, const JonesMatrix& sample, int output);

// Transmitted intensity for a modal sample, averaged over a band of width band_nm centred on the
// train's wavelength: every interference term cos(Δψ) becomes cos(Δψ)·sinc(Δψ'·band/2), the exact
// box average of a phase linear across the band. band_nm = 0 gives the monochromatic value. This
// is what lets a plate of any thickness integrate without aliasing (high orders average to white).
double modal_transmission(const TrainState& train, const ModalPoint& m, double band_nm);

}  // namespace pmsim
