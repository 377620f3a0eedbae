// Schlick's approximation against the Fresnel formulas (paper §2, Fig. 4): exact at normal
// incidence, its error grows toward grazing incidence. Checked on the formulas and on the render.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "core/base/units.h"
#include "core/optics/fresnel.h"
#include "core/optics/schlick.h"
#include "core/scene3d/experiment_images.h"
#include "core/scene3d/pinhole_camera.h"
#include "core/scene3d/scene3d_render.h"
#include "core/scene3d/scene3d_world.h"

namespace pmsim {
namespace {

double schlick_error(double theta_rad, double eta) {
  const double c = std::cos(theta_rad);
  return std::abs(schlick_reflectance(c, eta) - fresnel_reflectance_unpolarized(c, eta));
}

TEST(SchlickVsFresnel, ZeroAtNormalIncidenceLargestNearGrazing) {
  for (double eta : {1.5168, 1.78472}) {  // N-BK7 and N-SF11 at the d line, from air
    // At θ = 0 both reduce to R0 = ((1 − η)/(1 + η))²: equal to rounding (1e-15 relative).
    EXPECT_NEAR(schlick_error(0.0, eta), 0.0, 1e-16);
    double worst = 0.0, worst_deg = 0.0;
    for (int k = 0; k < 900; ++k) {
      const double deg = 0.1 * k;
      const double e = schlick_error(deg * pmsim::kPi / 180.0, eta);
      if (e > worst) {
        worst = e;
        worst_deg = deg;
      }
    }
    // Schlick (1994) fits (1 − cosθ)^5 to the unpolarized curve; the misfit peaks where the
    // Fresnel curve bends up steeply, beyond 70° for these indices (closed forms evaluated on a
    // 0.1° grid; the error near normal incidence is below 1e-3 of R0).
    EXPECT_GT(worst_deg, 70.0) << "eta " << eta;
    EXPECT_GT(worst, 10.0 * schlick_error(30.0 * pmsim::kPi / 180.0, eta)) << "eta " << eta;
    EXPECT_LT(schlick_error(5.0 * pmsim::kPi / 180.0, eta), 1e-3 * schlick_reflectance(1.0, eta));
  }
}

TEST(SchlickVsFresnel, Fig4DifferenceConcentratesWhereTheLensIsSeenAtGrazingIncidence) {
  std::ifstream in(std::string(PMSIM_SOURCE_DIR) + "/assets/scenes3d/fig4_lens_area_light.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["camera"]["width"] = 80;
  j["camera"]["height"] = 60;
  j["lights"][0]["samples"] = 2;
  j["render"]["fresnel"] = "schlick";
  const Scene3dImage s = render_scene3d(j, "fig4");
  j["render"]["fresnel"] = "exact";
  const Scene3dImage f = render_scene3d(j, "fig4");
  const Scene3dDescription d = parse_scene3d(j, "fig4");
  const Scene3dWorld world(d);
  const PinholeCamera cam(d.camera);
  double sum_normal = 0.0, sum_grazing = 0.0, sum_outside = 0.0;
  int n_normal = 0, n_grazing = 0, n_outside = 0;
  for (int y = 0; y < d.camera.height; ++y)
    for (int x = 0; x < d.camera.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * d.camera.width + x;
      double diff = 0.0;
      for (int c = 0; c < 3; ++c) diff += std::abs(s.rgb_linear[3 * i + c] - f.rgb_linear[3 * i + c]);
      const glm::dvec3 dir = cam.direction(x + 0.5, y + 0.5);
      Scene3dHit h;
      if (!world.intersect(cam.position(), dir, 0.0, std::numeric_limits<double>::infinity(), h) ||
          h.kind != Scene3dSurfaceKind::Lens) {
        sum_outside += diff;
        ++n_outside;
        continue;
      }
      const double cos_i = std::abs(glm::dot(dir, h.normal));
      if (cos_i > std::cos(20.0 * pmsim::kPi / 180.0)) {
        sum_normal += diff;
        ++n_normal;
      } else if (cos_i < std::cos(50.0 * pmsim::kPi / 180.0)) {
        sum_grazing += diff;
        ++n_grazing;
      }
    }
  ASSERT_GT(n_normal, 20);
  ASSERT_GT(n_grazing, 5);
  // Away from glass nothing depends on the reflectance model: identical to float rounding.
  EXPECT_LT(sum_outside / n_outside, 1e-6);
  // Entry within 20° of the normal: Schlick's error at the entry node is ≤ 3.3e-4 (n = 1.785);
  // entry beyond 50°: ≥ 1.5e-2, up to 3.4e-2 near 85° (closed forms). Deeper nodes meet other
  // angles, so the image ratio is smaller than the nodes' ~50; requiring 2 leaves room for scene
  // changes yet fails if the error were spread evenly over the lens.
  EXPECT_GT(sum_grazing / n_grazing, 2.0 * sum_normal / n_normal);
}

}  // namespace
}  // namespace pmsim
