#pragma once
// What a scene needs to be evaluated, compiled once per scene ("model only what the scene needs"),
// in named stages:
//   1. optical_domains   the specimen's domains (a plate, a wedge, the grains and twin lamellae of
//                        a section; core/microscope/optical_domains.h);
//   2. pixel_view        the evaluation units (one per domain in parallel light — a uniform plate
//                        is ONE spectral evaluation for the whole field —, one per thickness step
//                        of a wedge, one per pixel of a conoscopic figure) and for every pixel the
//                        units it shows with their weights (core/microscope/pixel_view.h);
//   3. choose_model_policy  plate model, lens model, exactness criteria and why
//                        (core/microscope/model_policy.h);
//   4. fit_modal_units   the modal fits of every unit (core/microscope/modal_units.h);
//   5. lens ghosts       of physical lenses in a conoscopic figure (core/microscope/lens_ghosts.h);
// and the model report written from the policy at the end. Read-only once compiled.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat2x2.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/plate.h"
#include "core/microscope/compensator.h"
#include "core/microscope/modal_units.h"
#include "core/microscope/model_policy.h"
#include "core/microscope/optical_domains.h"
#include "core/microscope/pixel_view.h"
#include "core/microscope/scene.h"
#include "core/optics/jones.h"

namespace pmsim {

class EvaluationPlan {
 public:
  const Scene& scene() const { return scene_; }
  int width() const { return scene_.render.width; }
  int height() const { return scene_.render.height; }

  // Stage 1: the specimen.
  const std::vector<OpticalDomain>& domains() const { return domains_.domains; }
  const SectionMap* section() const { return domains_.section.get(); }
  const CompensatorPlate& compensator() const { return compensator_; }
  // The plate of a domain prepared at a wavelength (mounting medium outside, Fresnel on).
  PreparedPlate prepare(int domain, double wavelength_nm) const;

  // Stage 2: the view.
  ViewKind view_kind() const { return view_.kind; }
  const std::vector<EvalUnit>& units() const { return view_.units; }
  const std::vector<int>& pixel_offset() const {
    return view_.pixel_offset;
  }  // refs of pixel i: [offset[i], offset[i+1])
  const std::vector<PixelRef>& refs() const { return view_.refs; }
  bool pixel_lit(std::size_t pixel) const {
    return view_.pixel_offset[pixel + 1] > view_.pixel_offset[pixel];
  }
  const std::vector<glm::dvec3>& cone_dirs() const { return view_.cone_dirs; }
  int spatial_samples() const { return view_.spatial_samples; }
  int dirs_of(const EvalUnit& u) const { return u.cone ? static_cast<int>(view_.cone_dirs.size()) : 1; }
  const glm::dvec3& dir(const EvalUnit& u, int d) const { return u.cone ? view_.cone_dirs[d] : u.k_air; }

  // Stage 3: the models.
  const ModelPolicy& policy() const { return policy_; }
  PlateModel plate_model() const { return policy_.plate_model; }
  const LensPolarizationTable* lenses() const { return policy_.lenses; }  // physical lens model; null = ideal
  // Condenser and objective Jones matrices for a direction (the aplanatic frame change alone for
  // ideal lenses).
  void lens_jones(const glm::dvec3& k_air, glm::dmat2& condenser, glm::dmat2& objective) const;
  // The whole sample-side train as one Jones matrix: objective · sample · condenser.
  JonesMatrix with_lenses(const JonesMatrix& sample, const glm::dvec3& k_air) const;

  // Stage 4: the modal fits (modal plate model; empty for the exact one).
  const std::vector<ModalTerms>& modal_terms() const {
    return modal_.terms;
  }  // unit u, direction d at u*dirs_per_unit+d
  int dirs_per_unit() const { return modal_.dirs_per_unit; }
  // The fits behind modal_terms(), indexed alike (compile_evaluation_plan's `keep_fits`; else
  // empty): their terms in other trains are make_modal_terms away.
  const std::vector<ModalFit>& modal_fits() const { return modal_.fits; }
  bool needs_exact(int unit) const {
    return policy_.plate_model == PlateModel::Exact ||
           (!modal_.unit_exact.empty() && modal_.unit_exact[unit]);
  }
  bool any_exact() const { return policy_.plate_model == PlateModel::Exact || policy_.exact_units > 0; }

  // Stage 5: ghost light of the physical lenses (optics.lens_depth ≥ 2, conoscopic figure): XYZ per
  // pixel (mono: T, T, T) added to the direct light; empty = none. Computed once per plan, not per
  // pass.
  const std::vector<float>& ghost_xyz() const { return ghost_xyz_; }

  // Which model each element uses and why (shown in the UI and the stats JSON).
  const std::string& model_report() const { return model_report_; }

  // The same plan evaluated with other modal terms (as many as modal_terms()): a comparison of fits.
  EvaluationPlan with_modal_terms(std::vector<ModalTerms> terms) const;

 private:
  friend std::shared_ptr<const EvaluationPlan> compile_evaluation_plan(const Scene&, const std::atomic<bool>*, bool);
  explicit EvaluationPlan(const Scene& scene) : scene_(scene) {}

  Scene scene_;
  OpticalDomains domains_;
  CompensatorPlate compensator_;
  PixelView view_;
  ModelPolicy policy_;
  ModalUnits modal_;
  std::vector<float> ghost_xyz_;
  std::string model_report_;
};

// Validates (InputError) and compiles. Fits the modal plates in parallel (TBB); `cancel` (may be
// null) aborts early, returning null. `keep_fits`: keep the modal fits (modal_fits(); a figure's
// probes evaluate one plan in nine trains).
std::shared_ptr<const EvaluationPlan> compile_evaluation_plan(const Scene& scene,
                                                              const std::atomic<bool>* cancel = nullptr,
                                                              bool keep_fits = false);

// The domain shown at image point (x_frac, y_frac) (0…1 from the left and from the top) in
// parallel light, or the one under the field centre in a conoscopic view; -1 outside any lit area.
int domain_at_image_point(const EvaluationPlan& plan, double x_frac, double y_frac);

}  // namespace pmsim
