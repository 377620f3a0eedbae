#pragma once
// What a scene needs to be evaluated, decided once per scene ("model only what the scene needs"):
// the optical domains (a plate, a wedge, the grains and twin lamellae of a section), the
// evaluation units (one per domain in parallel light — a uniform plate is ONE spectral evaluation
// for the whole field —, one per thickness step of a wedge, one per pixel of a conoscopic figure),
// and for every pixel the units it shows with their weights.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/crystal.h"
#include "core/microscope/compensator.h"
#include "core/microscope/modal_fit.h"
#include "core/microscope/scene.h"
#include "core/microscope/lens_polarization.h"
#include "core/microscope/section_map.h"
#include "core/optics/jones.h"

namespace pmsim {

struct OpticalDomain {
  const Crystal* crystal = nullptr;    // nullptr: nothing on the stage (or an isotropic layer)
  glm::dmat3 crystal_to_lab{1.0};      // stage rotation applied
  double thickness_um = 0.0;
  std::string mineral;
};

struct EvalUnit {
  int domain = 0;
  double thickness_um = 0.0;
  glm::dvec3 k_air{0.0, 0.0, 1.0};
  bool cone = false;                   // integrate over the illuminating cone instead of k_air
};

struct PixelRef {
  int unit = 0;
  float weight = 1.0f;
};

enum class PlateModel { Modal, Exact };

struct MicroscopeSetup {
  Scene scene;
  std::shared_ptr<Crystal> custom_crystal;       // sample.crystal, owned here
  std::shared_ptr<const SectionMap> section;
  std::vector<OpticalDomain> domains;
  std::vector<EvalUnit> units;
  std::vector<int> pixel_offset;                 // refs of pixel i: [pixel_offset[i], pixel_offset[i+1])
  std::vector<PixelRef> refs;
  CompensatorPlate compensator;
  std::vector<glm::dvec3> cone_dirs;             // directions (air) of the illuminating cone
  int spatial_samples = 1;                       // sub-pixel positions per pixel
  PlateModel plate_model = PlateModel::Modal;
  std::vector<ModalTerms> terms;                 // modal: unit u, direction d at u*dirs_per_unit+d
  int dirs_per_unit = 1;
  std::vector<char> unit_exact;                  // modal model: 1 = this unit needs the exact Jones matrix
  bool needs_exact(int unit) const {
    return plate_model == PlateModel::Exact || (!unit_exact.empty() && unit_exact[unit]);
  }
  std::string model_report;
  const LensPolarizationTable* lenses = nullptr;  // physical lens model; null = ideal
  // Ghost light of the physical lenses (optics.lens_depth ≥ 2, conoscopic view; core/microscope/
  // lens_ghosts.h): XYZ per pixel (mono: T, T, T) added to the direct light; empty = none.
  // Computed once per setup, not per pass.
  std::vector<float> ghost_xyz;

  // Condenser and objective Jones matrices for a direction (identity for ideal lenses).
  void lens_jones(const glm::dvec3& k_air, glm::dmat2& condenser, glm::dmat2& objective) const;
  // The whole sample-side train as one Jones matrix: objective · sample · condenser.
  JonesMatrix with_lenses(const JonesMatrix& sample, const glm::dvec3& k_air) const;

  int width() const { return scene.render.width; }
  int height() const { return scene.render.height; }
  int dirs_of(const EvalUnit& u) const { return u.cone ? static_cast<int>(cone_dirs.size()) : 1; }
  const glm::dvec3& dir(const EvalUnit& u, int d) const { return u.cone ? cone_dirs[d] : u.k_air; }
  // The plate of a domain prepared at a wavelength (mounting medium outside, Fresnel on).
  PreparedPlate prepare(int domain, double wavelength_nm) const;
};

// Validates (InputError) and builds. Fits the modal plates in parallel (TBB); `cancel` (may be
// null) aborts early, returning null.
std::shared_ptr<const MicroscopeSetup> build_setup(const Scene& scene,
                                                   const std::atomic<bool>* cancel = nullptr);

// The domain shown at image point (x_frac, y_frac) (0…1 from the left and from the top) in
// parallel light, or the one under the field centre in a conoscopic view; -1 outside any lit area.
int domain_at_image_point(const MicroscopeSetup& setup, double x_frac, double y_frac);

}  // namespace pmsim
