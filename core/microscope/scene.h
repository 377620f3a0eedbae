#pragma once
// Everything that defines what the microscope shows: the state a scene file stores, a `--set
// key=value` changes and a UI control edits. Field names follow the scene keys (dot paths in
// comments), which are a contract: scripts and saved scenes use them.
//
// Lab frame: x to the right of the image (east), y up (north), z along the microscope axis toward
// the observer; light travels +z; angles counter-clockwise as the observer sees them, from +x.
#include <array>
#include <map>
#include <optional>
#include <string>

#include "core/crystal/crystal_indices.h"  // CrystalIndices: sample.crystal
#include "core/optics/interface_model.h"   // FresnelModel: optics.schlick
#include "core/spectrum/colour_vision.h"
#include "core/spectrum/illuminant.h"

namespace pmsim {

// mode: ortho|cono. Setting mode (a scene file without a "bertrand" key, or --set mode=…) moves the
// Bertrand lens with it — cono: in, ortho: out — as the UI's one-click switch does; "bertrand" can
// then be flipped on its own (cono + bertrand out: the image plane lit by the convergent cone;
// ortho + bertrand in: the back focal plane in parallel light, a small bright spot).
enum class ViewMode { Ortho, Cono };
enum class SampleType { Plate, Wedge, Section, Grains };     // sample.type: plate|wedge|section|grains
// sample.nonindexed: what an EBSD map's non-indexed points show: the mounting medium (as a hole
// in the section) or nothing (black, opaque).
enum class NonIndexed { Medium, Black };
enum class Compensator { None, Gypsum, Mica, QuartzWedge };  // compensator: none|gypsum|mica|quartz_wedge
// illuminant: D65|A is pmsim::Illuminant (core/spectrum/illuminant.h)
enum class LensModel { Auto, Ideal, Physical };    // optics.lens_model: auto|ideal|physical
enum class RenderStrategy { Auto, Modal, Exact };  // render.strategy: auto|modal|exact

// sample.crystal is CrystalIndices (core/crystal/crystal_indices.h)

struct ObjectiveSettings {
  double magnification = 10.0;  // objective.magnification
  double na = 0.25;             // objective.na
  bool operator==(const ObjectiveSettings&) const = default;
};

// The eyepiece's field number: the diameter (mm) of its field stop, i.e. of the field seen in the
// intermediate image plane. At the specimen the field of view is field_number_mm / magnification
// (core/microscope/view_geometry.h).
struct EyepieceSettings {
  double field_number_mm = 20.0;  // eyepiece.field_number_mm
  bool operator==(const EyepieceSettings&) const = default;
};

// The mechanical stage: the point of the thin section under the crosshair, in section
// coordinates (mm, origin at the section's centre, x east, y north at stage 0°). The rotating
// stage (stage_deg) turns the section about that point.
struct StageSettings {
  double x_mm = 0.0;  // stage.x_mm
  double y_mm = 0.0;  // stage.y_mm
  bool operator==(const StageSettings&) const = default;
};

struct CondenserSettings {
  double na = 0.9;  // condenser.na (the cone that lights the conoscopic figure)
  // condenser.aperture_na: the aperture diaphragm in orthoscopic mode, the NA of the cone of
  // light reaching the specimen (0: parallel light, the diaphragm stopped down; core/specimen).
  double aperture_na = 0.0;
  bool operator==(const CondenserSettings&) const = default;
};

// sample.cut: a plate cut along a crystal plane of a library mineral with unit-cell and optical-
// orientation data, and the lattice direction in it that points north at stage 0° (text as
// written, e.g. {"plane": "(010)", "north": "[001]"}; core/crystal/crystal_cut.h). When set it
// replaces optic_axis / x_axis / z_axis for plates and wedges.
struct SampleCut {
  std::string plane;  // "(hkl)"
  std::string north;  // "[uvw]"
  bool operator==(const SampleCut&) const = default;
};

struct SampleSettings {
  SampleType type = SampleType::Plate;        // sample.type
  std::string mineral = "quartz";             // sample.mineral (a name in assets/minerals)
  std::optional<CrystalIndices> crystal;      // sample.crystal (replaces mineral when set)
  double thickness_um = 30.0;                 // sample.thickness_um (wedge: at the right edge)
  std::array<double, 3> optic_axis{1, 0, 0};  // sample.optic_axis (uniaxial), lab frame at stage 0°
  std::array<double, 3> x_axis{1, 0, 0};      // sample.x_axis (biaxial nα direction)
  std::array<double, 3> z_axis{0, 0, 1};      // sample.z_axis (biaxial nγ direction)
  std::optional<SampleCut> cut;               // sample.cut (replaces the three axes when set)
  std::string section;                        // sample.section (thin-section file in assets/sections,
                                              // or an EBSD map .ctf/.ang: core/microscope/map_section.h)
  std::string medium = "mounting";            // sample.medium (mounting medium name)
  // sample.phases: an EBSD map's phase names → library minerals ({"Garnet 2": "almandine"});
  // core/ebsd/phase_names.h resolves names it does not list.
  std::map<std::string, std::string> phases;
  NonIndexed nonindexed = NonIndexed::Medium;  // sample.nonindexed: medium|black
  // sample.medium_index: n_D of the immersion liquid of a grain mount (1.40…1.80), with the
  // dispersion of the liquid series in assets/liquids (core/specimen/immersion_liquid.h).
  // Unset: the mount uses 1.54.
  std::optional<double> medium_index;
  // sample.orientation_seed: every grain of a thin-section file redrawn in a random orientation
  // from this seed (0 … 2³¹ − 1; core/microscope/section_reorient.h), a new specimen of the same
  // rock. Unset: the file's orientations.
  std::optional<int> orientation_seed;
  // sample.seed: grows another specimen of a rock named by sample.section from its recipe
  // (assets/rocks, core/texture/rock_growth.h): every grain differs, the recipe's mode and
  // textures stay (0 … 2³¹ − 1). Unset: the recipe's shipped seed. Only rocks grown from a recipe
  // take it; a hand-placed section file cannot be grown again.
  std::optional<int> seed;
  bool operator==(const SampleSettings&) const = default;
};

struct RenderSettings {
  int width = 512;                                 // render.width
  int height = 512;                                // render.height
  int spp = 0;                                     // render.spp (0: until converged)
  int wavelengths = 0;                             // render.wavelengths (0: until converged)
  double single_wavelength_nm = 0.0;               // render.single_wavelength_nm (0: white light)
  double tolerance_de2000 = 0.5;                   // render.tolerance (stop when the estimate is below)
  RenderStrategy strategy = RenderStrategy::Auto;  // render.strategy: auto|modal|exact
  // render.native: on|off. On an EBSD map, one pixel per map point and the field framing the map
  // (core/microscope/native_resolution.h); no effect on other samples.
  bool native = false;
  // render.exposure_ev: stops of exposure of 8-bit outputs (PNG, the app's field), image × 2^ev
  // before encoding (core/render/exposure.h); −10…10, 0 as rendered.
  double exposure_ev = 0.0;
  // render.vision: normal|protanopia|deuteranopia|tritanopia. The 8-bit outputs and the app's
  // field as an observer with that colour-vision deficiency sees them (core/spectrum/
  // colour_vision.h); like the exposure, linear outputs stay the physical image.
  ColourVision vision = ColourVision::Normal;
  bool operator==(const RenderSettings&) const = default;
};

struct OpticsSettings {
  LensModel lens_model = LensModel::Auto;      // optics.lens_model
  int lens_depth = 1;                          // optics.lens_depth (dT for physical lenses)
  FresnelModel fresnel = FresnelModel::Exact;  // optics.schlick: true|false (true: Schlick, approximate)
  // optics.relief: on|off. On: a thin section in the orthoscopic view (analyzer out, or in without
  // a compensator) is traced as a refracting 3-D slab (core/specimen/traced_specimen.h): relief,
  // outlines, cleavage, focus. Off: the flat section image of the progressive renderer.
  bool relief = true;
  bool operator==(const OpticsSettings&) const = default;
};

struct Scene {
  ViewMode mode = ViewMode::Ortho;          // mode
  double polarizer_deg = 0.0;               // polarizer_deg (0 = E–W)
  double analyzer_deg = 90.0;               // analyzer_deg (90 = N–S)
  bool analyzer_in = true;                  // analyzer: in|out
  double stage_deg = 0.0;                   // stage_deg
  bool bertrand_in = false;                 // bertrand: in|out
  // focus_um: the fine focus, the objective raised by this many µm from the focus on the
  // specimen's mid-plane (+ = focusing up). Used by the refracting specimen (core/specimen).
  double focus_um = 0.0;
  Illuminant illuminant = Illuminant::D65;  // illuminant
  StageSettings stage;
  ObjectiveSettings objective;
  EyepieceSettings eyepiece;
  CondenserSettings condenser;
  SampleSettings sample;
  bool sample_in = true;                        // sample.present: false = empty stage
  Compensator compensator = Compensator::None;  // compensator
  double compensator_position = 0.0;            // compensator_position 0…1 (quartz wedge)
  RenderSettings render;
  OpticsSettings optics;
  bool operator==(const Scene&) const = default;
};

}  // namespace pmsim
