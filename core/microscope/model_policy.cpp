#include "core/microscope/model_policy.h"

#include <cstdio>
#include <sstream>

#include "core/microscope/direction_modal_table.h"
#include "core/microscope/radial_modal_table.h"
#include "core/microscope/view_geometry.h"

namespace pmsim {

ModelPolicy choose_model_policy(const Scene& scene, const std::vector<OpticalDomain>& domains,
                                const std::function<double(const LensPolarizationTable&)>& lens_difference) {
  ModelPolicy policy;
  const bool conoscopic_figure = scene.mode == ViewMode::Cono && scene.bertrand_in;
  const RenderStrategy strategy = scene.render.strategy;
  bool active = false;
  for (const OpticalDomain& d : domains)
    if (d.crystal && d.crystal->optically_active()) active = true;
  // Plate: modal unless the scene asks for the exact Jones matrix per wavelength.
  policy.single_wavelength = scene.render.single_wavelength_nm > 0;
  policy.plate_model =
      (strategy == RenderStrategy::Exact || policy.single_wavelength) ? PlateModel::Exact : PlateModel::Modal;
  const bool auto_white = strategy == RenderStrategy::Auto && !policy.single_wavelength;
  policy.exact.absorbing_in_field = auto_white && !conoscopic_figure;
  policy.exact.optically_active_near_axis = auto_white && active;
  // Lenses. In parallel light every ray runs along the axis, where the two models agree exactly
  // (the physical one is normalised to its axial transmission), so only oblique light can need
  // the physical model.
  policy.lens_model_asked = scene.optics.lens_model;
  policy.fresnel = scene.optics.fresnel;
  policy.oblique_light = scene.mode == ViewMode::Cono;
  if (scene.optics.lens_model == LensModel::Physical) {
    policy.lenses = &lens_polarization_table(scene.optics.fresnel);
  } else if (scene.optics.lens_model == LensModel::Auto && policy.oblique_light) {
    const LensPolarizationTable& table = lens_polarization_table(scene.optics.fresnel);
    policy.lens_difference_dL = lens_difference(table);
    if (*policy.lens_difference_dL > scene.render.tolerance_de2000) policy.lenses = &table;
  }
  return policy;
}

namespace {

std::string view_report(const PixelView& view) {
  std::ostringstream out;
  switch (view.kind) {
    case ViewKind::ConoscopicFigure:
      out << "view: conoscopic figure, one evaluation per pixel (" << view.units.size() << ")";
      break;
    case ViewKind::ParallelLightSpot:
      out << "view: back focal plane in parallel light (spot of sin θ = " << kParallelBeamSinTheta << ")";
      break;
    case ViewKind::Field:
      out << "view: "
          << (!view.cone_dirs.empty() ? "image plane in the convergent cone (" +
                                            std::to_string(view.cone_dirs.size()) + " directions)"
                                      : std::string("orthoscopic, parallel light"))
          << ", " << view.units.size() << " spectral evaluation" << (view.units.size() == 1 ? "" : "s")
          << " for the field";
      break;
  }
  return out.str();
}

std::string lens_report(const ModelPolicy& policy) {
  char buf[160];
  if (policy.lens_difference_dL) {
    std::snprintf(buf, sizeof buf,
                  policy.lenses
                      ? "; condenser, objective: physical SML lenses (auto: ideal would differ by ΔL*≈%.2f)"
                      : "; condenser, objective: ideal (auto: physical differs by ΔL*≈%.2f)",
                  *policy.lens_difference_dL);
    return buf;
  }
  if (policy.lenses)
    return std::string("; condenser, objective: physical SML lenses (Fresnel ") +
           (policy.fresnel == FresnelModel::Schlick ? "Schlick" : "exact") + ", depth-0 path)";
  return std::string("; condenser, objective: ideal (perfect imaging, polarization kept") +
         (policy.lens_model_asked == LensModel::Auto ? "; auto: exact for axial light)" : ")");
}

}  // namespace

std::string model_report(const ModelPolicy& policy, const PixelView& view) {
  std::ostringstream report;
  report << view_report(view);
  report << "; plate: "
         << (policy.plate_model == PlateModel::Exact
                 ? (policy.single_wavelength ? "exact Jones matrix (single wavelength)"
                                             : "exact Jones matrix per wavelength")
                 : "modal fit (3 mode solutions per direction, band-averaged interference)");
  report << lens_report(policy);
  report << "; Bertrand lens: ideal (images the back focal plane)";
  if (policy.radial_table)
    report << "; optic axis ⟂ stage: modal fits from a radial table of " << RadialModalTable::kEntries
           << " directions";
  if (policy.direction_table)
    report << "; one plate in every direction: modal fits from a " << DirectionModalTable::kSide << "² direction table";
  if (policy.exact_units > 0)
    report << "; exact Jones matrix for " << policy.exact_units << " of " << view.units.size()
           << " evaluations (absorbing crystals in parallel light; optically active ones near the axis)";
  if (policy.ghosts_traced) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "; lens ghosts (dT = %d): %d paths, objective %.3f %% + condenser %.3f %% of a white field",
                  policy.ghost_depth, policy.ghost_paths, policy.ghost_objective_percent,
                  policy.ghost_condenser_percent);
    report << buf;
  } else if (policy.lenses && view.kind == ViewKind::ConoscopicFigure) {
    report << "; lens ghosts: none (optics.lens_depth < 2: no internal reflection reaches the image)";
  }
  return report.str();
}

}  // namespace pmsim
