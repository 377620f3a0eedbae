#include "core/microscope/pixel_probe.h"

#include <algorithm>
#include <cmath>

#include "core/base/conventions.h"
#include "core/crystal/opacity.h"
#include "core/materials/medium.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/optical_train.h"
#include "core/microscope/view_geometry.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

PixelProbe probe_pixel(const Scene& scene_in, double x_frac, double y_frac) {
  Scene scene = scene_in;
  // The probe needs the domains, not the image: a tiny image keeps the set-up cheap while the
  // geometry (aspect ratio) stays that of the real one.
  const int W = scene.render.width, H = scene.render.height;
  const double shrink = std::max(1.0, std::max(W, H) / 8.0);
  scene.render.width = std::max(1, static_cast<int>(std::lround(W / shrink)));
  scene.render.height = std::max(1, static_cast<int>(std::lround(H / shrink)));
  scene.render.spp = 1;
  scene.render.strategy = RenderStrategy::Exact;
  const auto plan = compile_evaluation_plan(scene);
  PixelProbe p;
  x_frac = std::clamp(x_frac, 0.0, 1.0);
  y_frac = std::clamp(y_frac, 0.0, 1.0);
  const glm::dvec2 f = field_from_pixel(W, H, x_frac * W, y_frac * H);
  glm::dvec3 k = kLightDirection;
  const bool cono_bfp = scene.mode == ViewMode::Cono && scene.bertrand_in;
  if (cono_bfp) {
    if (!bfp_direction(scene, f, k)) return p;
  } else if (scene.mode == ViewMode::Ortho && scene.bertrand_in) {
    if (std::hypot(f.x, f.y) > kParallelBeamSinTheta / scene.objective.na) return p;
  }
  p.lit = true;
  const int dom =
      cono_bfp ? domain_at_image_point(*plan, 0.5, 0.5) : domain_at_image_point(*plan, x_frac, y_frac);
  const OpticalDomain& D = plan->domains()[std::max(0, dom)];
  p.mineral = D.mineral;
  p.thickness_um = D.thickness_um;
  if (scene.sample_in && scene.sample.type == SampleType::Wedge) {
    const glm::dvec2 at = cono_bfp ? glm::dvec2(0.0) : f;
    p.thickness_um = wedge_thickness_um(scene_in, sample_from_field(at, scene.stage_deg));
  }
  for (double nm = 380.0; nm <= 780.0 + 1e-9; nm += 5.0) {
    const TrainState train = make_train(scene, plan->compensator(), nm);
    JonesMatrix J = JonesMatrix::identity();
    if (D.crystal && p.thickness_um > 0) {
      PreparedPlate pp = plan->prepare(std::max(0, dom), nm);
      pp.thickness_um = p.thickness_um;
      J = plate_jones(pp, k);
    }
    const double t = jones_transmission(train, plan->with_lenses(J, k));
    p.wavelength_nm.push_back(nm);
    p.transmission.push_back(std::isfinite(t) ? t : 0.0);
  }
  p.opaque = D.crystal && p.thickness_um > 0 && is_opaque(*D.crystal, p.thickness_um);
  if (D.crystal && p.thickness_um > 0 && !p.opaque) {
    PreparedPlate pp = plan->prepare(std::max(0, dom), kOrderWavelengthNm);
    pp.thickness_um = p.thickness_um;
    p.retardation_nm = plate_modes(pp, k).retardation_nm;
  }
  p.order = p.retardation_nm / kOrderWavelengthNm;
  return p;
}

}  // namespace pmsim
