#pragma once
// The physical lens model: the condenser top lens and the objective front lens are SML lenses
// (core/lens; assets/lenses/paper_rl425_rs43.json — the paper's near-hemispheric N-BK7 lens),
// each with its focus on the specimen, 0.5 mm working distance. A ray leaving (or reaching) the
// specimen at angle θ crosses two air–glass faces at oblique incidence; Fresnel transmits its
// s and p components differently (t_s ≠ t_p, Born & Wolf §1.5.3), which turns the plane of
// polarization of oblique rays toward the meridional plane — the effect that bends and splits the
// isogyres of real conoscopic figures. By rotational symmetry s and p are the lens' eigen-
// polarizations, so one traced profile τ_s(θ), τ_p(θ) (depth-0 path, absorption included) gives
// every direction's Jones matrix; the condenser is the same lens reversed (reciprocity: equal
// power transmissions). Amplitudes are relative to the axial ray, so the exposure reference
// (Y = 1 on axis) is kept. Traced at 550 nm: the glass dispersion changes t_s/t_p by < 0.1 %
// across the visible. Ghost paths (internal reflections, optics.lens_depth) leave the lens in
// other directions and land elsewhere in the back focal plane: core/microscope/lens_ghosts.h.
#include <vector>

#include <glm/mat2x2.hpp>
#include <glm/vec3.hpp>

#include "core/lens/lens.h"
#include "core/optics/interface_model.h"

namespace pmsim {

// Where the physical model's lenses sit: the paper's lens (assets/lenses/paper_rl425_rs43.json)
// on the axis, its vertex kLensWorkingDistanceMm from the specimen — above it for the objective
// (side = +1), below for the condenser (side = −1) — traced at kPhysicalLensNm.
constexpr double kLensWorkingDistanceMm = 0.5;
constexpr double kPhysicalLensNm = 550.0;
LensSpec physical_lens_spec(int side = +1);

struct LensPolarizationTable {
  static constexpr int kSamples = 256;
  double max_sin = 0.999;            // table spans sin θ_air in [0, max_sin]
  std::vector<double> tau_s, tau_p;  // relative amplitude transmissions at sin θ = max_sin·i/(kSamples−1)
  // Real 2×2 Jones matrix of one lens for a ray along k_air, in transverse_basis(k_air).
  glm::dmat2 jones(const glm::dvec3& k_air) const;
};

// The polarization mapping of an ideal, aplanatic lens (Richards & Wolf, Proc. R. Soc. A 253, 358
// (1959)): a ray crossing the pupil at azimuth φ keeps its radial (p) and azimuthal (s) field
// components while the lens tilts it to k_air. Returns the real rotation from the lab pupil basis
// (x̂, ŷ) to transverse_basis(k_air); its transpose maps back (the objective). Identity on the
// axis and in the planes φ = 0°, 90° (so isogyres stay on the polarizer and analyzer).
glm::dmat2 aplanatic_frame(const glm::dvec3& k_air);

// Traced once per Fresnel model (cached). Throws InputError if the lens asset is missing.
const LensPolarizationTable& lens_polarization_table(FresnelModel fresnel);

}  // namespace pmsim
