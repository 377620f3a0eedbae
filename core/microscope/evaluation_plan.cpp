#include "core/microscope/evaluation_plan.h"

#include <algorithm>
#include <cassert>

#include "core/materials/medium.h"
#include "core/microscope/lens_ghosts.h"
#include "core/microscope/lens_model_difference.h"
#include "core/microscope/map_section.h"
#include "core/microscope/scene_check.h"
#include "core/microscope/view_geometry.h"

namespace pmsim {

PreparedPlate EvaluationPlan::prepare(int domain, double wavelength_nm) const {
  const OpticalDomain& d = domains_.domains[domain];
  PlateSpec spec;
  spec.crystal = d.crystal;
  spec.crystal_to_lab = d.crystal_to_lab;
  spec.thickness_um = d.thickness_um > 0 ? d.thickness_um : 1.0;
  spec.n_outside = find_medium(scene_.sample.medium).n(wavelength_nm);
  spec.fresnel = true;
  return prepare_plate(spec, wavelength_nm);
}

void EvaluationPlan::lens_jones(const glm::dvec3& k, glm::dmat2& condenser, glm::dmat2& objective) const {
  // Condenser: lab pupil → the ray's transverse basis (aplanatic mapping), then the physical
  // lens' s/p diattenuation; the objective the reverse. Same profile for both (reciprocity).
  const glm::dmat2 frame = aplanatic_frame(k);
  if (!policy_.lenses) {
    condenser = frame;
    objective = glm::transpose(frame);
    return;
  }
  const glm::dmat2 lens = policy_.lenses->jones(k);
  condenser = lens * frame;
  objective = glm::transpose(frame) * lens;
}

JonesMatrix EvaluationPlan::with_lenses(const JonesMatrix& sample, const glm::dvec3& k) const {
  glm::dmat2 condenser, objective;
  lens_jones(k, condenser, objective);
  return jones_from_real(objective) * sample * jones_from_real(condenser);
}

EvaluationPlan EvaluationPlan::with_modal_terms(std::vector<ModalTerms> terms) const {
  assert(terms.size() == modal_.terms.size());
  EvaluationPlan plan = *this;
  plan.modal_.terms = std::move(terms);
  return plan;
}

std::shared_ptr<const EvaluationPlan> compile_evaluation_plan(const Scene& scene, const std::atomic<bool>* cancel,
                                                              bool keep_fits) {
  check_scene(scene);
  std::shared_ptr<EvaluationPlan> plan(new EvaluationPlan(scene));
  plan->domains_ = optical_domains(scene);
  plan->compensator_ = make_compensator(scene.compensator, scene.compensator_position);
  std::optional<PixelView> view = pixel_view(scene, plan->domains_, cancel);
  if (!view) return nullptr;
  plan->view_ = std::move(*view);
  // lens_model_difference reads the domains and units only (the lenses are not chosen yet).
  plan->policy_ = choose_model_policy(scene, plan->domains(), [&](const LensPolarizationTable& table) {
    return lens_model_difference(*plan, table);
  });
  ModelPolicy& policy = plan->policy_;
  if (policy.plate_model == PlateModel::Modal) {
    std::optional<ModalUnits> modal = fit_modal_units(*plan, policy.exact, cancel, keep_fits);
    if (!modal) return nullptr;
    plan->modal_ = std::move(*modal);
    policy.radial_table = plan->modal_.radial_table;
    policy.direction_table = plan->modal_.direction_table;
    policy.exact_units = static_cast<std::size_t>(
        std::count(plan->modal_.unit_exact.begin(), plan->modal_.unit_exact.end(), 1));
  }
  if (policy.lenses && scene.optics.lens_depth >= 2 && plan->view_kind() == ViewKind::ConoscopicFigure) {
    LensGhostImage ghosts = lens_ghost_image(*plan, cancel);
    if (cancel && *cancel) return nullptr;
    plan->ghost_xyz_ = std::move(ghosts.xyz);
    std::size_t lit = 0;
    for (std::size_t i = 0; i + 1 < plan->pixel_offset().size(); ++i) lit += plan->pixel_lit(i);
    policy.ghosts_traced = true;
    policy.ghost_depth = scene.optics.lens_depth;
    policy.ghost_paths = ghosts.paths;
    policy.ghost_objective_percent = 100.0 * ghosts.objective_energy / std::max<std::size_t>(1, lit);
    policy.ghost_condenser_percent = 100.0 * ghosts.condenser_energy / std::max<std::size_t>(1, lit);
  }
  plan->model_report_ = model_report(policy, plan->view_);
  // An EBSD map: what the evaluation reduced it to (core/microscope/map_section.h).
  if (const SectionMap* s = plan->section())
    if (const MapSectionFacts* f = map_section_facts(*s))
      plan->model_report_ += "; " + map_section_summary(*f);
  return plan;
}

int domain_at_image_point(const EvaluationPlan& plan, double x_frac, double y_frac) {
  const Scene& sc = plan.scene();
  const glm::dvec2 f = field_from_pixel(sc.render.width, sc.render.height, x_frac * sc.render.width,
                                        y_frac * sc.render.height);
  if (sc.mode == ViewMode::Cono && sc.bertrand_in) {
    glm::dvec3 k;
    if (!bfp_direction(sc, f, k)) return -1;
    // The figure is that of the grain under the crosshair.
    return plan.section() ? plan.section()->domain_at(FieldToSection(sc)({0.0, 0.0})) : 0;
  }
  return (plan.section() && sc.sample_in) ? plan.section()->domain_at(FieldToSection(sc)(f)) : 0;
}

}  // namespace pmsim
