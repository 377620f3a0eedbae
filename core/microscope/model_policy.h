#pragma once
// The model policy of an evaluation plan: which plate model, which lens model, which units must be
// exact although the plan is modal, and why ("model only what the scene needs"). The report shown
// in the UI and in the stats JSON (`model_report`) is written from it once the plan is compiled.
//
// render.strategy: auto (the cheapest accurate plate model per scene), modal (eigenmodes fitted
// across the spectrum, band-averaged interference terms), exact (the plate's Jones matrix at every
// wavelength sample, plain midpoint quadrature: the paper's uniform sampling).
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/microscope/lens_polarization.h"
#include "core/microscope/optical_domains.h"
#include "core/microscope/pixel_view.h"
#include "core/microscope/scene.h"

namespace pmsim {

enum class PlateModel { Modal, Exact };

// Units of a modal plan that need the exact Jones matrix per band all the same.
struct ExactnessCriteria {
  // Absorbing (pleochroic) crystals in the image plane: the fit interpolates their transmission
  // from its three anchor wavelengths, which left the biotite grains of the granite at mean ΔE00
  // 0.7 where exact Jones matrices per band reach 0.1. In parallel light a grain is one
  // evaluation for the whole field, so exactness costs nothing worth saving; per-pixel figures
  // keep the fit.
  bool absorbing_in_field = false;
  // Optically active crystals where their rotation is not small against the linear phase: the fit
  // carries linear eigenmodes only, and optical activity makes them elliptical near the optic axis.
  bool optically_active_near_axis = false;
};

struct ModelPolicy {
  PlateModel plate_model = PlateModel::Modal;
  bool single_wavelength = false;  // render.single_wavelength_nm > 0 (one reason for Exact)
  ExactnessCriteria exact;         // modal model only

  // Lenses (condenser and objective; the Bertrand lens is always ideal).
  LensModel lens_model_asked = LensModel::Auto;   // optics.lens_model
  FresnelModel fresnel = FresnelModel::Exact;     // optics.schlick: the physical lenses' Fresnel
  bool oblique_light = false;                     // convergent light: the only case where lenses differ
  const LensPolarizationTable* lenses = nullptr;  // the physical lens model; null = ideal
  std::optional<double> lens_difference_dL;       // auto in oblique light: mean ΔL*, ideal vs physical

  // What the later stages found (fit_modal_units, the lens ghosts).
  bool radial_table = false;    // modal fits interpolated from a RadialModalTable
  bool direction_table = false;  // modal fits interpolated from a DirectionModalTable
  std::size_t exact_units = 0;  // units of a modal plan evaluated exactly (ExactnessCriteria)
  bool ghosts_traced = false;   // lens ghosts added (physical lenses, dT ≥ 2, conoscopic figure)
  int ghost_depth = 0;          // optics.lens_depth (dT) of the traced ghosts
  int ghost_paths = 0;
  double ghost_objective_percent = 0.0, ghost_condenser_percent = 0.0;  // of a white field
};

// The plate model, exactness criteria and lens model of a scene whose specimen has `domains`.
// `lens_difference` measures the mean ΔL* between the ideal and the physical lenses; it is called
// only for optics.lens_model = auto in oblique light (physical when it exceeds render.tolerance).
ModelPolicy choose_model_policy(const Scene& scene, const std::vector<OpticalDomain>& domains,
                                const std::function<double(const LensPolarizationTable&)>& lens_difference);

// The report of a compiled plan: its view, then each element's model and why.
std::string model_report(const ModelPolicy& policy, const PixelView& view);

}  // namespace pmsim
