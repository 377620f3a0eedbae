#pragma once
// What one grain of a thin section is and shows in the current view, computed from its
// indicatrix and its crystallography (core/crystal/section_optics.h): the ground truth of
// pmsim-render --grains and of the app's teaching panel for the grain under the cursor.
//
// Frames. The section frame is that of docs/conventions.md (mm, x east, y north, z toward the
// observer, at stage 0°); section normal +z. A grain's SectionGrain::orientation has the
// indicatrix X, Y, Z as columns in it; a mineral's crystallography gives them in the crystal
// Cartesian frame of lattice.h (indicatrix_axes), so lattice_to_section = orientation ·
// indicatrix_axesᵀ. Image angles are counter-clockwise from image +x at the current stage angle:
// the stage turns the section by +stage_deg, so image angle = section angle + stage_deg,
// reduced to [0°, 180°) (lines, not arrows).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/crystal/section_optics.h"
#include "core/microscope/scene.h"
#include "core/microscope/section_map.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

// Indices for the vibration directions and extinction positions: the sodium D line, the
// wavelength optical-mineralogy tables quote (Nesse 2012 ch. 7). Retardation: at 550 nm, the
// first-order red of the gypsum plate and the Michel-Lévy chart's reference.
constexpr double kGrainReportIndexWavelengthNm = kMineralTableDNm;
constexpr double kGrainReportRetardationWavelengthNm = kOrderWavelengthNm;

struct GrainTwinReport {
  std::string law;                           // SectionGrain::twin_law
  std::vector<double> extinction_stage_deg;  // of the twin individual (odd lamellae)
  // A cross-hatched grain's second set (SectionGrain::cross_twin): its law and the extinction of
  // its individual (odd lamellae of the second set, even of the first); empty otherwise.
  std::string cross_law;
  std::vector<double> cross_extinction_stage_deg;
};

// A grain with undulose extinction (SectionGrain subgrains): its bands and how far its extinction
// sweeps across the grain, the range of the host's slow-direction angle over the bands within
// the grain's longest radius of its centre (0 when the bend axis lies in the section along the
// vibration directions; not defined in a circular section).
struct GrainSubgrainReport {
  double width_mm = 0.0, step_deg = 0.0;
  std::optional<double> extinction_sweep_deg;
};

// A grain whose cracks are veins of a secondary mineral (SectionGrain::vein: serpentine in olivine).
struct GrainAlterationReport {
  std::string mineral;
  double vein_mm = 0.0;
};

// A grain with inclusions (SectionGrain::inclusions: the quartz trails of a garnet porphyroblast).
// Trail directions are image angles [0, 180): at the inclusions' outer limit and in the core (the
// same unless the grain turned as it grew; the core's differs by rotation_deg).
struct GrainInclusionReport {
  std::string mineral;
  double size_mm = 0.0;
  double rim_trail_deg = 0.0, core_trail_deg = 0.0, rotation_deg = 0.0;
  // Each inclusion's pleochroic halo (SectionGrain::InclusionSet::Halo): its radius from the
  // inclusion's centre and the host's absorption factor there; 0 and 1 without one.
  double halo_radius_mm = 0.0, halo_darkening = 1.0;
  std::string habit = "trail";  // "needle": each along its own elongation (InclusionSet::Needle); "wedge": triangles (InclusionSet::wedges)
};

// A detrital grain with overgrowth cement (SectionGrain::Overgrowth): the scale of its euhedral
// form, the radius of its detrital core's outline in the section (the dust line's circle, about
// the grain's centre) and the dust's mineral ("" without a dust line).
struct GrainOvergrowthReport {
  double habit_scale = 1.0, detrital_radius_mm = 0.0;
  std::string dust_mineral;
};

// A grain with myrmekite (SectionGrain::Myrmekite): the mineral its bulbs grow into, how many
// bulbs stand in this section, and the quartz rods' mineral and extinction positions (one
// orientation for all of the grain's rods).
struct GrainMyrmekiteReport {
  std::string host;
  int bulbs = 0;
  std::string quartz_mineral;
  std::vector<double> quartz_extinction_stage_deg;
};

struct GrainReport {
  int id = 0;           // the grain's label (SectionMap::grain_label)
  std::string mineral;  // as the section file names it, composition included ("plagioclase:An35")
  // Bunge (φ1, Φ, φ2) of lattice_to_section, degrees; empty when the mineral has no unit cell and
  // optical orientation (then no cleavage traces or habit either).
  std::optional<std::array<double, 3>> euler_deg;
  long long area_px = 0;  // pixels of the label image with this id (report_grains; 0 from report_grain)
  std::vector<double> cleavage_traces_deg;  // image angles [0, 180), one per cleavage plane with a trace
  std::optional<double> elongation_deg;     // image angle [0, 180) of the elongation, if any
  // Stage angles in [0°, 180°) at which the grain is extinct between crossed polars (a vibration
  // direction parallel to the polarizer), ascending; empty when it is extinct at every angle
  // (isotropic, or cut ⟂ an optic axis).
  std::vector<double> extinction_stage_deg;
  std::optional<double> extinction_angle_deg;  // [0, 45] to the first cleavage trace, else the elongation
  std::optional<SignOfElongation> sign_of_elongation;  // empty without an elongation or when indeterminate
  double retardation_nm = 0.0;  // sample.thickness_um · (n′γ − n′α) at 550 nm
  // Image angle [0, 180) of the slow vibration direction (n′γ; the fast one is ⟂ it); empty in a
  // circular section. What the app's overlay draws.
  std::optional<double> slow_vibration_deg;
  std::optional<GrainTwinReport> twin;
  std::optional<GrainSubgrainReport> subgrains;
  std::optional<GrainAlterationReport> alteration;
  std::optional<GrainInclusionReport> inclusions;
  std::optional<GrainOvergrowthReport> overgrowth;
  std::optional<GrainMyrmekiteReport> myrmekite;
  // Opaque (magnetite, ilmenite: core/crystal/opacity.h at the section's thickness): black in plane
  // and crossed light, so nothing above is observable in transmitted light — the extinction
  // positions, slow direction, extinction angle, sign of elongation and twin extinctions are left
  // empty and the retardation 0; the shape (elongation) and the lattice (euler_deg) still are given.
  bool opaque = false;
  // The indicatrix is a stand-in on the crystal frame (SectionGrain::optics_stand_in: the mineral
  // file has no optical_orientation, plagioclase today), so the extinction stage
  // angles, extinction angle, sign of elongation and slow direction above are those of the
  // stand-in, not the real mineral's (issue 22). False ("published"): the mineral file has an
  // optical_orientation, or the grain is isotropic or uniaxial given by its optic axis (nothing
  // to place but that).
  bool optics_stand_in = false;
};

// The report of grain `label` (1 … grains.size(); std::out_of_range otherwise) in `scene` (stage
// angle, polarizer, thickness). area_px is left 0: it is a property of an image.
GrainReport report_grain(const Scene& scene, const SectionMap& section, int label);

// One report per grain present in the label image (count > 0), ascending id, area_px filled.
std::vector<GrainReport> report_grains(const Scene& scene, const SectionMap& section,
                                       const std::vector<std::uint16_t>& labels);

const char* sign_of_elongation_name(SignOfElongation s);  // "length-slow", "length-fast", "indeterminate"

// --grains' "optics": "stand-in" or "published" (GrainReport::optics_stand_in).
const char* grain_optics_name(const GrainReport& r);
// The teaching panel's line for a stand-in grain, saying its extinction angles are not the real
// mineral's; empty for a published one.
std::string grain_optics_warning(const GrainReport& r);

}  // namespace pmsim
