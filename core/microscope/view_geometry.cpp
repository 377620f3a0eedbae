#include "core/microscope/view_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/base/conventions.h"

namespace pmsim {

glm::dvec2 field_from_pixel(int width, int height, double px, double py) {
  const double half = 0.5 * std::min(width, height);
  return {(px - 0.5 * width) / half, (0.5 * height - py) / half};
}

StageToSample::StageToSample(double stage_deg) {
  const double a = -radians(stage_deg);
  c = std::cos(a);
  s = std::sin(a);
}

glm::dvec2 sample_from_field(const glm::dvec2& f, double stage_deg) { return StageToSample(stage_deg)(f); }

double field_of_view_mm(const Scene& scene) {
  return scene.eyepiece.field_number_mm / scene.objective.magnification;
}

double mm_per_pixel(const Scene& scene, int width, int height) {
  return field_of_view_mm(scene) / std::min(width, height);
}

FieldToSection::FieldToSection(const Scene& scene)
    : rotate(scene.stage_deg),
      half_fov_mm(0.5 * field_of_view_mm(scene)),
      centre_mm(scene.stage.x_mm, scene.stage.y_mm) {}

glm::dvec2 section_point_from_pixel(const Scene& scene, int width, int height, double px, double py) {
  return FieldToSection(scene)(field_from_pixel(width, height, px, py));
}

bool bfp_direction(const Scene& scene, const glm::dvec2& f, glm::dvec3& k_air) {
  const double rho = std::sqrt(f.x * f.x + f.y * f.y);  // field coordinates are O(1)
  if (!bfp_lit(scene, rho)) return false;
  const double sin_t = rho * scene.objective.na;
  const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin_t * sin_t));
  if (rho > 0) {
    k_air = {sin_t * f.x / rho, sin_t * f.y / rho, cos_t};
  } else {
    k_air = kLightDirection;
  }
  return true;
}

double field_half_width(int width, int height) {
  return static_cast<double>(width) / std::min(width, height);
}

double wedge_thickness_um(const Scene& scene, const glm::dvec2& p) {
  const double W = field_half_width(scene.render.width, scene.render.height);
  const double u = (p.x + W) / (2.0 * W);
  return scene.sample.thickness_um * std::clamp(u, 0.0, 1.0);
}

}  // namespace pmsim
