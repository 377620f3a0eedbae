#pragma once
// What the Becke line does at one point of a grain-mount image (the teaching panel's probe): the
// fragment under the point, the index it offers to light vibrating along the polarizer, and the
// liquid's n_D, both at the D line. The Becke line is the bright fringe of light refracted (and
// totally reflected) toward the medium of higher index at an inclined boundary; on focusing up
// (focus_um increasing) it moves into that medium (Nesse 2012, Introduction to Optical
// Mineralogy, §4 "Becke line"). The values come from the same SpecimenScene the renderer traces.
#include <string>

#include <glm/vec3.hpp>

#include "core/microscope/scene.h"
#include "core/specimen/specimen_scene.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

// The Becke-line probes' wavelength: the sodium D line, where immersion liquids and mounting
// media are specified (n_D).
constexpr double kBeckeWavelengthNm = kLiquidDNm;
// |n' − n_D| below which the outline of a 30–300 µm fragment is no longer seen as a line but as
// the colour fringes of a near match (the precision of the immersion method, Nesse 2012 §4).
constexpr double kBeckeMatch = 0.001;

struct BeckeProbe {
  bool on_fragment = false;   // the point lies over a fragment (else over liquid)
  int fragment = -1;          // nearest fragment index in the mount (the one under the point if on_fragment)
  double mineral_n = 0.0;     // n' of that fragment along the polarizer at 589.26 nm
  double liquid_n = 0.0;      // n_D of the liquid
  // +1: the line moves into the mineral on focusing up (n' > n_D of the liquid); −1: into the
  // liquid; 0: matched within 0.001 (the outline nearly vanishes, dispersion colours remain).
  int moves_into_mineral = 0;
  // The fragment's two vibration directions for vertical light (the central section of its
  // indicatrix ⟂ the microscope axis): their indices n'α ≤ n'γ at 589.26 nm (equal for an
  // isotropic mineral), what sets its interference colour between crossed polars.
  double n_fast = 0.0, n_slow = 0.0;
};

// What one fragment offers to light at the D line: n′ along `vibration` (a unit horizontal vector
// in the stage frame) and the two vibration indices of vertical light (equal for an isotropic
// fragment), and its relief sign against the liquid (+1 higher, −1 lower, 0 within kBeckeMatch).
// The probe and the ground truth (grain_mount_truth.h) both read fragments through this.
struct FragmentOptics {
  double n_vibration = 0.0, n_fast = 0.0, n_slow = 0.0, liquid_n = 0.0;
  int relief = 0;
};
FragmentOptics fragment_optics(const SpecimenScene& specimen, int fragment, const glm::dvec3& vibration);

// `x`, `y`: fractions of the image from its top left (as the app's probe). The mount is `specimen`
// (grain_mount_specimen(scene)); the view (stage, field, polarizer) is `scene`'s.
BeckeProbe probe_becke_line(const SpecimenScene& specimen, const Scene& scene, double x, double y);
// One line for the teaching panel: what the student sees when focusing up here.
std::string describe_becke_line(const BeckeProbe& probe);
// One line for the teaching panel with the analyzer in: where the fragment's colour comes from.
std::string describe_crossed_polars(const BeckeProbe& probe);

}  // namespace pmsim
