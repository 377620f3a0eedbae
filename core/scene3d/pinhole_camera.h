#pragma once
// The pinhole camera of a scene3d description: image plane at unit distance, vertical field of
// view fov_deg, pixel (0,0) at the top left. Optional ideal linear polarizer in front of it.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <cmath>

#include "core/base/units.h"
#include "core/scene3d/scene3d_description.h"

namespace pmsim {

class PinholeCamera {
 public:
  explicit PinholeCamera(const Scene3dCamera& c) : cam_(c) {
    fwd_ = glm::normalize(c.look_at - c.position);
    right_ = glm::normalize(glm::cross(fwd_, c.up));
    up_ = glm::cross(right_, fwd_);
    half_h_ = std::tan(0.5 * c.fov_deg * kPi / 180.0);
    half_w_ = half_h_ * c.width / c.height;
    if (c.filter_angle_deg) {
      const double a = *c.filter_angle_deg * kPi / 180.0;
      filter_dir_ = std::cos(a) * right_ + std::sin(a) * up_;
    }
  }
  const glm::dvec3& position() const { return cam_.position; }
  // Unit direction through image point (x, y) in pixels (x + 0.5 is a pixel centre).
  glm::dvec3 direction(double x, double y) const {
    const double px = x / cam_.width * 2.0 - 1.0;
    const double py = 1.0 - y / cam_.height * 2.0;
    return glm::normalize(fwd_ + px * half_w_ * right_ + py * half_h_ * up_);
  }
  bool has_filter() const { return cam_.filter_angle_deg.has_value(); }
  // The filter is a sheet ⟂ the optical axis; the field it passes along an oblique ray is its
  // axis projected onto the ray's transverse plane.
  glm::dvec3 filter_axis(const glm::dvec3& d) const {
    return glm::normalize(filter_dir_ - glm::dot(filter_dir_, d) * d);
  }
  const glm::dvec3& right() const { return right_; }
  const glm::dvec3& up() const { return up_; }

 private:
  Scene3dCamera cam_;
  glm::dvec3 fwd_, right_, up_, filter_dir_{1.0, 0.0, 0.0};
  double half_h_ = 1.0, half_w_ = 1.0;
};

}  // namespace pmsim
